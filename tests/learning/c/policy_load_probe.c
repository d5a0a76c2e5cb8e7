/*
 * Saved-parameter probe (test code): loads each array of policy_load_data.h into a fresh policy
 * of its image and prints svl_policy_load's answer ("L<k> 00" accepted, "L<k> ff" refused);
 * tests/learning/test_c_policy.py gives the same arrays to the Python loader.
 */
#include "swarmvm.h"
#include "swarmvm_learn.h"
#include "probe_io.h"
#include "policy_load_data.h"

static svm_vm_t vm;
static svl_policy_t policy;
static int32_t theta[LOAD_THETA];

int main(void)
{
    uint8_t k, answer;
    probe_start();
    svm_init(&vm);
    if (svm_load(&vm, load_image, sizeof load_image) != SVM_OK) {
        return 1;
    }
    for (k = 0; k < LOAD_CASES; k++) {
        svl_policy_init(&policy, &vm, theta, LOAD_THETA, 256, 6554, 4);
        answer = svl_policy_load(&policy, load_words[k], LOAD_WORDS) == 0 ? 0x00u : 0xFFu;
        probe_putc('L');
        probe_hex(&k, 1);
        probe_putc(' ');
        probe_hex(&answer, 1);
        probe_putc('\n');
    }
    probe_end();
    return 0;
}
