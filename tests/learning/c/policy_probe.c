/*
 * Learned-policy probe (test code): for each run of policy_data.h, load the run's table image,
 * choose with svl_policy (SVM_POLICY_LEARNED), credit every choice with the run's reward for
 * the chosen event, save the parameters half way and load them into a fresh policy (the flat
 * array round trip), make uncontrollable events occur at random, and print the chosen events ("C<k> hh hh ...", ff = none) and the final
 * saved array ("P<k> ..."). tests/learning/test_c_policy.py runs the same with the Python VM.
 * With -DPOLICY_ALL_SOURCES (AVR, SVM_IMAGE_SOURCES = SVM_ANY_SOURCE) run k loads its image
 * from flash, RAM or EEPROM (k % 3), so the policy reads the image wherever it lives.
 */
#include "swarmvm.h"
#include "swarmvm_learn.h"
#include "probe_io.h"
#include "policy_data.h"

static svm_vm_t vm;
static svl_policy_t policy;
static int32_t theta[POLICY_THETA_CAP];
static uint32_t words[POLICY_THETA_CAP + SVL_POLICY_HEADER_WORDS + 1];
static uint8_t chosen;
static uint32_t inputs;

#if defined(__AVR__) && defined(POLICY_ALL_SOURCES)
#include <avr/eeprom.h>
#define EEPROM_IMAGE_AT ((uint8_t *)1)      /* not 0: a null pointer means no image */
static uint8_t ram_image[POLICY_MAX_IMAGE];

static int load_image(uint8_t run, const uint8_t *image, uint16_t length)
{
    uint16_t i;
    if (run % 3u == 1u) {
        for (i = 0; i < length; i++) {
            ram_image[i] = pgm_read_byte(image + i);
        }
        return svm_load(&vm, ram_image, length);
    }
    if (run % 3u == 2u) {
        for (i = 0; i < length; i++) {
            eeprom_update_byte(EEPROM_IMAGE_AT + i, pgm_read_byte(image + i));
        }
        return svm_load_E(&vm, EEPROM_IMAGE_AT, length);
    }
    return svm_load_P(&vm, image, length);
}
#else
#define load_image(run, image, length) svm_load_P(&vm, (image), (length))
#endif

/* Uncontrollable events occur at random (about 1 poll in 6), from the probe's own xorshift32
 * so that the VM's generator is left to the policy; actions do nothing. */
static uint8_t dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    (void)event;
    if (op != SVM_OP_CHECK) {
        return 0;
    }
    inputs ^= inputs << 13;
    inputs ^= inputs >> 17;
    inputs ^= inputs << 5;
    return (uint8_t)((inputs >> 24) < 40u);
}

/* The chooser hook, recording what the policy chose. */
static uint8_t record(svm_vm_t *machine, const uint8_t *enabled, uint8_t count, void *ctx)
{
    chosen = svl_policy_choose(machine, enabled, count, ctx);
    return chosen;
}

static void tag(char letter, uint8_t run)
{
    probe_putc(letter);
    probe_hex(&run, 1);
}

int main(void)
{
    uint8_t run;
    probe_start();
    for (run = 0; run < POLICY_RUNS; run++) {
        struct policy_run r;
        int32_t rewards[POLICY_MAX_EVENTS];
        uint16_t step, count, i;
        PROBE_READ(&r, &policy_runs[run], sizeof r);
        PROBE_READ(rewards, policy_rewards[run], sizeof rewards);
        svm_init(&vm);
        if (load_image(run, policy_images[r.image], r.image_length) != SVM_OK) {
            probe_puts("load failed\n");
            break;
        }
        svm_set_options(&vm, SVM_POLICY_LEARNED, r.seed);
        svm_reset(&vm);
        svl_policy_init(&policy, &vm, theta, POLICY_THETA_CAP, r.inv_temp_q8, r.rate_q16, r.shift);
        svm_set_chooser(&vm, record, &policy);
        svm_set_dispatch(&vm, dispatch);
        inputs = r.seed ^ 0x5A5A5A5AUL;
        tag('C', run);
        for (step = 0; step < r.steps; step++) {
            chosen = 0xFF;
            svm_step(&vm);
            probe_putc(' ');
            probe_hex(&chosen, 1);
            if (chosen != 0xFF) {
                svl_policy_reward(&policy, rewards[chosen]);
            }
            if (step == r.steps / 2) {
                count = svl_policy_save(&policy, words, sizeof words / sizeof words[0]);
                svl_policy_init(&policy, &vm, theta, POLICY_THETA_CAP, 1, 0, 0);
                if (svl_policy_load(&policy, words, count) != 0) {
                    probe_puts(" reload failed");
                }
            }
        }
        count = svl_policy_save(&policy, words, sizeof words / sizeof words[0]);
        probe_putc('\n');
        tag('P', run);
        for (i = 0; i < count; i++) {
            probe_putc(' ');
            probe_u32(words[i]);
        }
        probe_putc('\n');
    }
    probe_puts("END\n");
    probe_end();
    return 0;
}
