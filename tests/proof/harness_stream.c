/* Eva harness over runtime_c/swarmvm_stream.c (with swarmvm.c's svm_validate and svm_load; make
 * prove; docs/proof.md).
 *
 * A receiver with a buffer of PROOF_MAX_IMAGE bytes takes an unknown number of chunks (a loop Eva
 * widens), each of 9 unknown bytes: any sequence number (in order, repeated, skipped, a restart
 * at 0) and any data (a corrupted chunk is one of them). Whenever it reports a complete image,
 * the image is loaded into a VM, as the streaming Kilobot does between two steps (the steps of
 * any image in that build are the kilobot-stream configuration's, so they are not repeated
 * here: they would double the run's time). */
#include "__fc_builtin.h"
#include "swarmvm.h"
#include "swarmvm_stream.h"

void Frama_C_show_each_reached(void);

#ifndef PROOF_MAX_IMAGE
#define PROOF_MAX_IMAGE 512
#endif

static uint8_t buffer[PROOF_MAX_IMAGE];
static svm_stream_t stream;
static svm_vm_t vm;

int main(void)
{
    uint8_t chunk[SVM_CHUNK_BYTES];
    svm_init(&vm);
    svm_stream_init(&stream, buffer, PROOF_MAX_IMAGE);
    while (Frama_C_nondet(0, 1)) {
        Frama_C_make_unknown((char *)chunk, sizeof chunk);
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        if (svm_stream_feed(&stream, chunk) == SVM_STREAM_COMPLETE) {
            (void)svm_load(&vm, buffer, svm_stream_length(&stream));
        }
    }
    return 0;
}
