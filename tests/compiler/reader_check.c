/* The C side of tests/compiler/test_reader_parity.py: prints svm_load's result code (SVM_OK or an
 * SVM_ERR_* code) for each image file named on the command line, one per line. Each image sits
 * in a heap buffer of exactly its size, so that a sanitizer build catches any read past it. */
#include <stdio.h>
#include <stdlib.h>

#include "swarmvm.h"

static int check(const char *path)
{
    FILE *file = fopen(path, "rb");
    long size;
    uint8_t *image;
    svm_vm_t vm;
    int result;
    if (file == NULL || fseek(file, 0, SEEK_END) != 0 || (size = ftell(file)) < 0 || size > 65535L ||
        fseek(file, 0, SEEK_SET) != 0) {
        fprintf(stderr, "%s: cannot read an image of at most 65535 bytes\n", path);
        return -1;
    }
    image = malloc(size > 0 ? (size_t)size : 1u);
    if (image == NULL || fread(image, 1, (size_t)size, file) != (size_t)size) {
        fprintf(stderr, "%s: read failed\n", path);
        return -1;
    }
    fclose(file);
    svm_init(&vm);
    result = svm_load(&vm, image, (uint16_t)size);
    free(image);
    return result;
}

int main(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        int result = check(argv[i]);
        if (result < 0) {
            return 2;
        }
        printf("%d\n", result);
    }
    return 0;
}
