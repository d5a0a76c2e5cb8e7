/*
 * API checks of the swarmvm C core that the trace harness does not reach, run on the host by
 * test_c_host.py: every refusal code of svm_load and that a refused image leaves the running
 * logic untouched; names; rebinding by name on a swap (names permuted into one long cycle,
 * half the events bound); a swap refused for a missing name; the violation hook; the learned
 * policy's chooser; policy first with a priority list, and one rebound by name on a swap; a
 * check bound to a controllable event. Images come from the generated
 * api_cases.h; each line printed is "<what> <value>", compared by the test.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "swarmvm.h"
#include "api_cases.h"

static svm_vm_t vm;
static svm_binding_t table[SVM_MAX_EVENTS];
static uint8_t tags[SVM_MAX_EVENTS];
static unsigned hook_calls, last_fired;

static void on_violation(svm_vm_t *machine, uint8_t event, uint8_t sup)
{
    (void)machine;
    (void)event;
    (void)sup;
    hook_calls++;
}

static unsigned char always(void *data)
{
    (void)data;
    return 1;
}

static void fired(void *data)
{
    last_fired = *(uint8_t *)data;
}

/* The chooser picks the last enabled event (never what `first` would). */
static uint8_t last_enabled(svm_vm_t *machine, const uint8_t *enabled, uint8_t count, void *ctx)
{
    *(unsigned *)ctx += 1;
    return svm_mask_nth(enabled, svm_mask_bytes(machine), (uint8_t)(count - 1u));
}

int main(void)
{
    unsigned k, e, ok, chooser_calls = 0;
    uint8_t states[SVM_MAX_SUPERVISORS];

    for (k = 0; k < NUM_BAD; k++) {
        printf("validate %s %d\n", bad_names[k], svm_validate(bad_images[k], bad_lengths[k], 0));
    }

    svm_init(&vm);
    printf("load %d\n", svm_load(&vm, image_a, sizeof image_a));
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    for (e = 0; e < svm_num_events(&vm); e++) {
        tags[e] = (uint8_t)e;
    }
    for (e = 0; e < 3; e++) {
        (void)svm_step(&vm);
    }
    for (e = 0; e < svm_num_supervisors(&vm); e++) {
        states[e] = (uint8_t)svm_state(&vm, (uint8_t)e);
    }
    ok = svm_load(&vm, bad_images[0], bad_lengths[0]) != SVM_OK && vm.image == image_a;
    for (e = 0; e < svm_num_supervisors(&vm); e++) {
        ok = ok && states[e] == svm_state(&vm, (uint8_t)e);
    }
    printf("refused_keeps_logic %u\n", ok);

    printf("index_EV %d\n", svm_event_index(&vm, "EV_" PROBE_NAME));
    printf("index_bare %d\n", svm_event_index(&vm, PROBE_NAME));
    printf("index_unknown %d\n", svm_event_index(&vm, "EV_noSuchEvent"));
    printf("bind_unknown_index %d\n", svm_bind(&vm, (uint8_t)svm_num_events(&vm), fired, 0, 0));
    printf("check_on_controllable %d\n", svm_bind(&vm, CONTROLLABLE_EVENT, 0, always, 0));

    /* Bind every other event, then swap in the image whose names are rotated by one. */
    for (e = 0; e < svm_num_events(&vm); e += 2) {
        (void)svm_bind(&vm, (uint8_t)e, fired, 0, &tags[e]);
    }
    printf("swap_rotated %d\n", svm_load(&vm, image_rotated, sizeof image_rotated));
    ok = 1;
    for (e = 0; e < svm_num_events(&vm); e++) {
        unsigned old = (e + 1u) % svm_num_events(&vm);   /* rotated: new name e = old name e+1 */
        if (old % 2u == 0u) {
            ok = ok && table[e].action == fired && table[e].data == &tags[old];
        } else {
            ok = ok && table[e].action == 0 && table[e].data == 0;
        }
    }
    printf("rebound_by_name %u\n", ok);
    printf("swap_missing_name %d\n", svm_load(&vm, image_missing, sizeof image_missing));
    printf("missing_keeps_logic %u\n", (unsigned)(vm.image == image_rotated));

    /* Violation hook: every uncontrollable check true, level mode, on a model that forbids some
     * of them in some states. */
    svm_init(&vm);
    (void)svm_load(&vm, image_violating, sizeof image_violating);
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    for (e = 0; e < svm_num_events(&vm); e++) {
        (void)svm_bind(&vm, (uint8_t)e, fired, svm_is_controllable(&vm, (uint8_t)e) ? 0 : always, &tags[e]);
    }
    svm_set_on_violation(&vm, on_violation);
    for (e = 0; e < 5; e++) {
        (void)svm_step(&vm);
    }
    printf("violations %u hook %u\n", (unsigned)svm_violations(&vm), hook_calls);

    /* Learned policy: the chooser decides; without a chooser nothing controllable fires. The
     * model has two controllable events enabled from its initial state. */
    svm_init(&vm);
    (void)svm_load(&vm, image_choice, sizeof image_choice);
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    for (e = 0; e < svm_num_events(&vm); e++) {
        (void)svm_bind(&vm, (uint8_t)e, fired, 0, &tags[e]);
    }
    svm_set_options(&vm, SVM_POLICY_LEARNED, 1);
    svm_reset(&vm);
    printf("learned_without_chooser %u\n", (unsigned)svm_step(&vm));
    svm_set_chooser(&vm, last_enabled, &chooser_calls);
    {
        uint8_t enabled[SVM_MASK_BYTES];
        uint8_t count = svm_enabled(&vm, enabled);
        uint8_t expected = svm_mask_nth(enabled, svm_mask_bytes(&vm), (uint8_t)(count - 1u));
        last_fired = 255;
        (void)svm_step(&vm);
        printf("learned_choice %u calls %u\n", (unsigned)(last_fired == expected && count > 1u), chooser_calls);
    }

    /* Policy first with a priority list: the listed event wins over the lower index. */
    {
        static const uint8_t prefer[1] = {PRIORITY_EVENT};
        svm_set_options(&vm, SVM_POLICY_FIRST, 1);
        svm_reset(&vm);
        last_fired = 255;
        (void)svm_step(&vm);
        printf("first_plain %u\n", last_fired);
        svm_set_priority(&vm, prefer, 1);
        svm_reset(&vm);
        (void)svm_step(&vm);
        printf("first_priority %u\n", last_fired);
    }

    /* A priority list bound with svm_bind_priority follows its names on a swap (image_rotated:
     * new name e = old name e+1); an image lacking one of them is refused, the list unchanged. */
    {
        static uint8_t ranked[2] = {0, 2};
        svm_init(&vm);
        (void)svm_load(&vm, image_a, sizeof image_a);
        svm_bind_priority(&vm, ranked, 2);
        k = (unsigned)svm_load(&vm, image_rotated, sizeof image_rotated);
        printf("priority_swap %u %u %u\n", k, ranked[0], ranked[1]);
        k = (unsigned)svm_load(&vm, image_missing, sizeof image_missing);
        printf("priority_missing %u %u %u\n", k, ranked[0], ranked[1]);
    }
    return 0;
}
