/*
 * Cycle counts of the learning code on the ATmega328P (AVR only; benchmarks/learning.py runs it
 * in simavr). Timer1 runs at the CPU clock, so its count is cycles (each measured call stays
 * below 65,536 cycles). Prints "K <name> <cycles hex>" lines.
 */
#include "swarmvm.h"
#include "swarmvm_learn.h"
#include "probe_io.h"
#include "cycles_data.h"

static svl_classifier_t model;
static svm_vm_t vm;
static svl_policy_t policy;
static int32_t theta[CYCLES_THETA_CAP];

static void start(void)
{
    TCCR1A = 0;
    TCCR1B = (uint8_t)(1 << CS10);
    TCNT1 = 0;
}

static void report(const char *name)
{
    uint16_t cycles = TCNT1;
    probe_puts("K ");
    probe_puts(name);
    probe_putc(' ');
    probe_hex(&cycles, 2);
    probe_putc('\n');
}

int main(void)
{
    static const svl_real mean[3] = {3500.0, 2.75, 50.0};
    static const svl_real scale[3] = {1443.38, 1.299, 28.87};
    static const svl_real seed_points[6] = {1000.0, 0.5, 100.0, 6000.0, 5.0, 0.0};
    static const uint8_t seed_labels[2] = {1, 0};
    svl_real x[3] = {2500.0, 1.5, 70.0};
    uint8_t i, yes = 0;
    probe_start();
    svl_classifier_init(&model, 3, mean, scale, (svl_real)0.01);
    svl_classifier_fit(&model, seed_points, seed_labels, 2, 1000, (svl_real)1e-3, 5);
    start();
    yes = svl_classifier_decide(&model, x);
    report("decide");
    start();
    svl_classifier_partial_fit(&model, x, yes);
    report("partial_fit");
    start();
    (void)svl_classifier_bid_value(&model, x);
    report("bid_value");
    svm_init(&vm);
    svm_load_P(&vm, cycles_image, sizeof cycles_image);
    svm_set_options(&vm, SVM_POLICY_UNIFORM, 1);
    svm_reset(&vm);
    start();
    svm_step(&vm);
    report("step_uniform");
    svm_set_options(&vm, SVM_POLICY_LEARNED, 1);
    svm_reset(&vm);
    svl_policy_init(&policy, &vm, theta, CYCLES_THETA_CAP, 256, 6554, 4);
    svm_set_chooser(&vm, svl_policy_choose, &policy);
    for (i = 0; i < 50; i++) {                /* learn a little so the preferences differ */
        svm_step(&vm);
        svl_policy_reward(&policy, 65536L);
    }
    start();
    svm_step(&vm);
    report("step_learned");
    start();
    svl_policy_reward(&policy, -65536L);
    report("reward");
    probe_puts("END\n");
    probe_end();
    return 0;
}
