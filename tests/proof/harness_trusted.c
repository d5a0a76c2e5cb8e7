/* Eva harness over runtime_c/swarmvm.c in its minimal profile (SVM_TRUSTED_IMAGE; make prove;
 * docs/proof.md). The profile runs only the image compiled into it, unchecked (the compiler
 * checked it when it wrote it), so the image here is not unknown bytes but a generated one:
 * proof_image.h, which prove.py writes into its work folder from the configuration's model
 * (proof_image, its bytes; the -D limits are the image's counts, as the generated build's are).
 * svm_init, the dispatch (a check answering an unknown 0 or 1), a violation hook where the build
 * keeps one, svm_load_P of the image (refused: any other pointer), unknown options and seed,
 * svm_reset, and an unknown number of steps in a loop (Eva widens it). */
#include "__fc_builtin.h"
#include "swarmvm.h"
#include "proof_image.h"

void Frama_C_show_each_reached(void);

static svm_vm_t vm;
static uint8_t other[sizeof proof_image];

static uint8_t dispatch(svm_vm_t *v, uint8_t event, uint8_t op)
{
    (void)v;
    (void)event;
    return op == SVM_OP_CHECK ? (uint8_t)Frama_C_interval(0, 1) : 0u;
}

#if SVM_WITH_VIOLATIONS
static void violation(svm_vm_t *v, uint8_t event, uint8_t supervisor)
{
    (void)v;
    (void)event;
    (void)supervisor;
}
#endif

int main(void)
{
    uint32_t seed;
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
#if SVM_WITH_VIOLATIONS
    svm_set_on_violation(&vm, violation);
#endif
    if (svm_load_P(&vm, other, sizeof other) == SVM_OK) {
        return 1;                               /* the profile runs no other bytes */
    }
    if (svm_load_P(&vm, proof_image, sizeof proof_image) != SVM_OK) {
        return 1;
    }
    Frama_C_make_unknown((char *)&seed, sizeof seed);     /* any seed (int may be 16 bits) */
    svm_set_options(&vm, (uint8_t)Frama_C_interval(0, 15), seed);
    svm_reset(&vm);
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        (void)svm_step(&vm);
    }
    return 0;
}
