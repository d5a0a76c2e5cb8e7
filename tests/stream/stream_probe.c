/* Host probe for runtime_c/swarmvm_stream.c: reads 9-byte chunks from stdin (binary), feeds
 * them to a stream with a buffer of STREAM_CAPACITY bytes, prints one status per chunk, and on
 * SVM_STREAM_COMPLETE swaps the image into a VM and prints its event count. */
#include <stdio.h>

#include "swarmvm.h"
#include "swarmvm_stream.h"

#ifndef STREAM_CAPACITY
#define STREAM_CAPACITY 512
#endif

int main(void)
{
    static uint8_t buffer[STREAM_CAPACITY];
    uint8_t chunk[SVM_CHUNK_BYTES];
    svm_stream_t stream;
    svm_vm_t vm;
    svm_init(&vm);
    svm_stream_init(&stream, buffer, sizeof buffer);
    while (fread(chunk, 1, sizeof chunk, stdin) == sizeof chunk) {
        uint8_t status = svm_stream_feed(&stream, chunk);
        printf("%u", (unsigned)status);
        if (status == SVM_STREAM_INVALID) {
            printf(":%u", (unsigned)stream.error);
        }
        if (status == SVM_STREAM_COMPLETE) {
            int loaded = svm_load(&vm, buffer, svm_stream_length(&stream));
            printf(":%d:%u", loaded, (unsigned)svm_num_events(&vm));
        }
        printf("\n");
    }
    return 0;
}
