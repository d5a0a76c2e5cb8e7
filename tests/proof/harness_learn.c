/* Eva harness over runtime_c/swarmvm_learn.c's learned selection policy (with swarmvm.c; make
 * prove; docs/proof.md). The image as in harness_core.c (PROOF_MAX_IMAGE unknown bytes, an
 * unknown length); on an accepted image, the policy bound to it (theta: PROOF_THETA words, an
 * unknown capacity up to that, unknown temperature, rate and baseline shift), as the chooser of
 * the learned policy; then an unknown number of steps, each followed by an unknown reward, and
 * at any point saved parameters loaded back from PROOF_WORDS unknown words (a corrupted store)
 * and the policy saved. The classifier (floating point, the host's learner) is not analysed. */
#include "__fc_builtin.h"
#include "swarmvm.h"
#include "harness_load.h"
#include "swarmvm_learn.h"

void Frama_C_show_each_reached(void);

#ifndef PROOF_MAX_IMAGE
#define PROOF_MAX_IMAGE 512
#endif
#ifndef PROOF_THETA
#define PROOF_THETA 128         /* the example's SVM_KILOBOT_THETA */
#endif
#define PROOF_WORDS (SVL_POLICY_HEADER_WORDS + PROOF_THETA + 1u)

static uint8_t unknown_image[PROOF_MAX_IMAGE];
static svm_vm_t vm;
static svl_policy_t policy;
static int32_t theta[PROOF_THETA];
static uint32_t words[PROOF_WORDS];

static uint8_t dispatch(svm_vm_t *v, uint8_t event, uint8_t op)
{
    (void)v;
    (void)event;
    return op == SVM_OP_CHECK ? (uint8_t)Frama_C_interval(0, 1) : 0u;
}

int main(void)
{
    uint16_t length = (uint16_t)Frama_C_interval(0, PROOF_MAX_IMAGE);
    int32_t reward;
    uint16_t u16[2];
    uint8_t shift;
    Frama_C_make_unknown((char *)unknown_image, PROOF_MAX_IMAGE);
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    if (proof_load(&vm, unknown_image, length) != SVM_OK) {
        return 0;
    }
    Frama_C_make_unknown((char *)u16, sizeof u16);
    Frama_C_make_unknown((char *)&shift, sizeof shift);
    if (svl_policy_init(&policy, &vm, theta, (uint16_t)Frama_C_interval(0, PROOF_THETA), u16[0], u16[1], shift) != 0) {
        return 0;
    }
    svm_set_chooser(&vm, svl_policy_choose, &policy);
    svm_set_options(&vm, (uint8_t)(SVM_POLICY_LEARNED | Frama_C_interval(0, 3)), 1u);
    svm_reset(&vm);
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        (void)svm_step(&vm);
        Frama_C_make_unknown((char *)&reward, sizeof reward);
        (void)svl_policy_reward(&policy, reward);
        if (Frama_C_nondet(0, 1)) {
            Frama_C_make_unknown((char *)words, sizeof words);
            (void)svl_policy_load(&policy, words, (uint16_t)Frama_C_interval(0, PROOF_WORDS));
        }
        if (Frama_C_nondet(0, 1)) {
            (void)svl_policy_save(&policy, words, (uint16_t)Frama_C_interval(0, PROOF_WORDS));
        }
    }
    return 0;
}
