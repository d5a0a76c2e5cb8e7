/* libFuzzer harness over the C runtime's image reader and step (runtime_c/swarmvm.c), built with
 * clang -fsanitize=fuzzer,address,undefined, once with the format's own maxima as limits and
 * once like a Kilobot build, exact masks and one-byte states (tests/fuzz/campaign.py's C_BUILDS;
 * docs/fuzzing.md).
 *
 * An input is a table image. It is tried as it is and resealed (length field and checksum
 * fitted, so that mutations reach the layout checks). An image svm_load accepts is then run
 * under every option combination (level/edge inputs, after-inputs/if-quiet control, each policy)
 * for STEPS steps with checks drawn from a generator seeded by the input, runtime bindings on
 * every event, a priority list bound by name, the inspection calls, and finally a swap to the
 * same image (rebinding by name). The property: no sanitizer report, no crash, no hang; and
 * the VM's own invariants, checked below (states inside their supervisors, events fired below
 * the event count). Each image sits in a heap buffer of exactly its size: a read past it is an
 * AddressSanitizer report. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "swarmvm.h"

#define STEPS 32u

typedef struct {
    uint32_t rng;
    uint32_t actions;
} fuzz_env_t;

static fuzz_env_t env;

static uint32_t next_random(void)
{
    env.rng ^= env.rng << 13;
    env.rng ^= env.rng >> 17;
    env.rng ^= env.rng << 5;
    return env.rng;
}

static unsigned char check(void *data)
{
    (void)data;
    return (unsigned char)(next_random() & 1u);
}

static void action(void *data)
{
    (void)data;
    env.actions++;
}

static uint8_t choose(svm_vm_t *vm, const uint8_t *enabled, uint8_t count, void *ctx)
{
    (void)ctx;
    /* Any event, enabled or not, or none: the VM must cope (it fires nothing then). */
    return next_random() & 1u ? svm_mask_nth(enabled, svm_mask_bytes(vm), (uint8_t)(next_random() % count))
                              : (uint8_t)next_random();
}

static void violation(svm_vm_t *vm, uint8_t event, uint8_t supervisor)
{
    if (event >= svm_num_events(vm) || supervisor >= svm_num_supervisors(vm)) {
        abort();
    }
}

static uint16_t crc16(const uint8_t *data, size_t length)
{
    uint16_t crc = 0xFFFFu;
    size_t i;
    int bit;
    for (i = 0; i < length; i++) {
        crc ^= data[i];
        for (bit = 0; bit < 8; bit++) {
            crc = (uint16_t)(crc & 1u ? (crc >> 1) ^ 0x8408u : crc >> 1);
        }
    }
    return crc;
}

/* The VM's invariants after a step: every supervisor in one of its own states. */
static void check_states(const svm_vm_t *vm)
{
    uint8_t s;
    for (s = 0; s < svm_num_supervisors(vm); s++) {
        if (svm_global_state(vm, s) != svm_first_state(vm, s) + svm_state(vm, s) ||
            svm_global_state(vm, s) >= svm_num_states(vm)) {
            abort();
        }
    }
}

static void inspect(const svm_vm_t *vm)
{
    uint8_t e, enabled[SVM_MASK_BYTES], count = svm_enabled(vm, enabled);
    char name[255], small[4];
    if (count > svm_num_events(vm)) {
        abort();
    }
    for (e = 0; e < svm_num_events(vm); e++) {
        (void)svm_weight(vm, e);
        (void)svm_is_controllable(vm, e);
        (void)svm_is_public(vm, e);
        (void)svm_event_name(vm, e, small, sizeof small);
        uint8_t length = svm_event_name(vm, e, name, (uint8_t)sizeof name);
        if (length > 0 && length < sizeof name && svm_event_index(vm, name) < 0) {   /* whole names find their event */
            abort();
        }
    }
}

static void run(const uint8_t *image, uint16_t length, uint32_t seed)
{
    static svm_binding_t bindings[255];
    static uint8_t priority[4];
    svm_vm_t vm;
    uint8_t options, e, k;
    uint32_t step;
    for (options = 0; options < 16u; options++) {
        int valid = svm_validate(image, length, SVM_SOURCE_RAM);
        svm_init(&vm);
        svm_set_bindings(&vm, bindings, 255);
        if (svm_load(&vm, image, length) != valid) {      /* the same checks, the same code */
            abort();
        }
        if (valid != SVM_OK) {
            return;
        }
        env.rng = seed | 1u;
        for (e = 0; e < svm_num_events(&vm); e++) {
            (void)svm_bind(&vm, e, action, svm_is_controllable(&vm, e) ? 0 : check, &env);
        }
        for (k = 0; k < sizeof priority; k++) {
            priority[k] = (uint8_t)(next_random() % (svm_num_events(&vm) + 1u));
        }
        svm_bind_priority(&vm, priority, sizeof priority);
        svm_set_chooser(&vm, choose, 0);
        svm_set_on_violation(&vm, violation);
        svm_set_options(&vm, options, seed);     /* 0..15: every SVM_INPUTS_*, SVM_CONTROL_*, SVM_POLICY_* */
        svm_reset(&vm);
        for (step = 0; step < STEPS; step++) {
            uint8_t fired = svm_step(&vm);
            if (fired > svm_num_events(&vm) + 1u) {
                abort();
            }
            check_states(&vm);
        }
        inspect(&vm);
        if (svm_load(&vm, image, length) != SVM_OK) {   /* a swap to itself rebinds every name */
            abort();
        }
        (void)svm_step(&vm);
        check_states(&vm);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    uint8_t *image;
    uint32_t seed = 2166136261u;
    size_t i;
    if (size > 0xFFFFu) {
        return 0;
    }
    for (i = 0; i < size; i++) {
        seed = (seed ^ data[i]) * 16777619u;
    }
    image = malloc(size > 0 ? size : 1u);
    if (image == NULL) {
        return 0;
    }
    memcpy(image, data, size);
    run(image, (uint16_t)size, seed);
    if (size >= SVM_MIN_IMAGE_SIZE) {
        uint16_t crc;
        image[SVM_AT_LENGTH] = (uint8_t)(size & 0xFFu);
        image[SVM_AT_LENGTH + 1u] = (uint8_t)(size >> 8);
        crc = crc16(image, size - SVM_CRC_SIZE);
        image[size - 2u] = (uint8_t)(crc & 0xFFu);
        image[size - 1u] = (uint8_t)(crc >> 8);
        run(image, (uint16_t)size, seed);
    }
    free(image);
    return 0;
}
