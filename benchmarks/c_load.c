/*
 * Image loads per second of the C VM on the host, for benchmarks/c_host.py: svm_load of the
 * compiled-in image of a conformance batch (svm_cases.h), in RAM, repeated for about a second
 * of wall time in rounds; prints the best round's rate.
 *
 *   c_load [ROUNDS]
 */
#include "swarmvm.h"
#include "svm_cases.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double seconds(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    static svm_vm_t vm;
    int rounds = argc > 1 ? atoi(argv[1]) : 5, r;
    long loads = 1000, i;
    double best = 0.0;
    svm_init(&vm);
    for (r = 0; r < rounds; r++) {
        double start = seconds(), elapsed;
        for (i = 0; i < loads; i++) {
            if (svm_load(&vm, svm_case_image, SVM_CASES_IMAGE_LEN) != SVM_OK) {
                fprintf(stderr, "c_load: the image was refused\n");
                return 1;
            }
        }
        elapsed = seconds() - start;
        if (elapsed < 0.05) {       /* too short to time: more loads per round */
            loads *= 4;
            r--;
            continue;
        }
        if ((double)loads / elapsed > best) {
            best = (double)loads / elapsed;
        }
    }
    printf("%.0f\n", best);
    return 0;
}
