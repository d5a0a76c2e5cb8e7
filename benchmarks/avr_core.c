/*
 * The VM core as a Kilobot program uses it, for benchmarks/avr_cycles.py to measure its flash
 * and RAM: the compiled-in image (svm_cases.h, a conformance batch) loaded from flash, then
 * stepped forever with callbacks through a compile-time dispatch. Nothing else is linked, so
 * `swarmvm footprint` of this program gives the core's bytes alone.
 */
#include "swarmvm.h"
#include "svm_cases.h"

static svm_vm_t vm;
static volatile uint8_t input;      /* what the checks read: not known to the compiler */

static uint8_t dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    return (uint8_t)(op == SVM_OP_CHECK ? (input >> (event & 7u)) & 1u : 0u);
}

int main(void)
{
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    if (svm_load_P(&vm, svm_case_image, SVM_CASES_IMAGE_LEN) != SVM_OK) {
        return 1;
    }
    for (;;) {
        input = svm_step(&vm);
    }
}
