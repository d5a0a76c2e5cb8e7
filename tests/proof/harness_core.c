/* Eva harness over runtime_c/swarmvm.c (make prove; docs/proof.md).
 *
 * The image: PROOF_MAX_IMAGE bytes of unknown values (Frama_C_make_unknown), of an unknown length
 * 0 .. PROOF_MAX_IMAGE (Frama_C_interval), at the start of a buffer of exactly PROOF_MAX_IMAGE
 * bytes: a read outside the buffer is an alarm, a read between `length` and the buffer's end is
 * not (Eva does not relate offsets to the length; docs/proof.md, "What is not proved").
 * svm_init, the dispatch, a violation hook, the chooser (an unknown event), svm_load; then, on an
 * accepted image, every event bound (an action, and a check answering an unknown 0 or 1 on the
 * uncontrollable ones), an unknown priority list, unknown options and seed, svm_reset, and an
 * unknown number of steps in a loop (Eva widens it: not an unrolled count). The build's limits
 * and features come from the -D flags of tests/proof/prove.py's CONFIGS, one configuration per target build. */
#include "__fc_builtin.h"
#include "swarmvm.h"
#include "harness_load.h"

void Frama_C_show_each_reached(void);
#if PROOF_UNKNOWN_CALL
int proof_unknown(void);
#endif

#ifndef PROOF_MAX_IMAGE
#define PROOF_MAX_IMAGE 512
#endif

static uint8_t unknown_image[PROOF_MAX_IMAGE];
#if SVM_WITH_NAMES
static char query[260];     /* a C string of any 0 .. 259 characters, for the name look-ups */
#endif
static svm_vm_t vm;
#if SVM_WITH_BINDINGS
static svm_binding_t table[SVM_MAX_EVENTS];
#endif
#if SVM_WITH_FIRST
static uint8_t priority[4];
#endif

static unsigned char check(void *data)
{
    (void)data;
    return (unsigned char)Frama_C_interval(0, 1);
}

static void action(void *data)
{
    (void)data;
}

static uint8_t dispatch(svm_vm_t *v, uint8_t event, uint8_t op)
{
    (void)v;
    (void)event;
    return op == SVM_OP_CHECK ? (uint8_t)Frama_C_interval(0, 1) : 0u;
}

static void violation(svm_vm_t *v, uint8_t event, uint8_t supervisor)
{
    (void)v;
    (void)event;
    (void)supervisor;
}

#if SVM_WITH_LEARNED
static uint8_t choose(svm_vm_t *v, const uint8_t *enabled, uint8_t count, void *ctx)
{
    (void)v;
    (void)enabled;
    (void)count;
    (void)ctx;
    return (uint8_t)Frama_C_interval(0, 255);    /* any event, enabled or not */
}
#endif

int main(void)
{
    uint16_t length = (uint16_t)Frama_C_interval(0, PROOF_MAX_IMAGE);
    uint32_t seed;
    Frama_C_make_unknown((char *)unknown_image, PROOF_MAX_IMAGE);
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    svm_set_on_violation(&vm, violation);
#if SVM_WITH_LEARNED
    svm_set_chooser(&vm, choose, 0);
#endif
#if PROOF_UNKNOWN_CALL
    /* tests/proof: a call of a function with neither code nor contract, which must fail the run. */
    if (proof_unknown() != 0) {
        return 1;
    }
#endif
#if PROOF_PLANT
    /* tests/proof: a planted defect the comparison must catch (a read past the image). */
    if (unknown_image[(uint16_t)Frama_C_interval(0, PROOF_MAX_IMAGE)] == 0u) {
        return 1;
    }
#endif
    if (proof_load(&vm, unknown_image, length) != SVM_OK) {
        return 0;
    }
#if SVM_WITH_BINDINGS
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    for (uint8_t e = 0; e < svm_num_events(&vm); e++) {
        (void)svm_bind(&vm, e, action, svm_is_controllable(&vm, e) ? 0 : check, 0);
    }
#endif
#if SVM_WITH_FIRST
    Frama_C_make_unknown((char *)priority, sizeof priority);
    svm_set_priority(&vm, priority, (uint8_t)Frama_C_interval(0, sizeof priority));
#endif
    Frama_C_make_unknown((char *)&seed, sizeof seed);     /* any seed (int may be 16 bits) */
    svm_set_options(&vm, (uint8_t)Frama_C_interval(0, 15), seed);
    svm_reset(&vm);
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
#if SVM_WITH_NAMES
        if (Frama_C_nondet(0, 1)) {             /* a look-up of any name, with or without its NUL */
            Frama_C_make_unknown(query, sizeof query - 1u);
            query[sizeof query - 1u] = '\0';
            (void)svm_event_index(&vm, query);
            (void)svm_event_index_n(&vm, query, (uint8_t)Frama_C_interval(0, 255));
        }
#endif
        (void)svm_step(&vm);
    }
    return 0;
}
