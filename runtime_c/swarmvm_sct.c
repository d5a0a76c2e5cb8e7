/* Nadzoru 2 compatible C API (see swarmvm_sct.h): a thin layer over one swarmvm VM, with the
 * published generic C VM's step in exact mode (SVM_SCT_EXACT=1). */
#include "swarmvm_sct.h"

#if SVM_SCT_EXACT
#ifndef SVM_SCT_RANDOM
#define SVM_SCT_RANDOM rand
#else
/* A generator given by name is declared here, so that this file needs no header of its library:
 * SVM_SCT_RANDOM_TYPE is its return type, by default uint8_t as kilolib's rand_soft(). */
#ifndef SVM_SCT_RANDOM_TYPE
#define SVM_SCT_RANDOM_TYPE uint8_t
#endif
SVM_SCT_RANDOM_TYPE SVM_SCT_RANDOM(void);
#endif
#endif

static svm_vm_t sct_vm;
static svm_binding_t sct_bindings[SVM_MAX_EVENTS];
static int sct_status = SCT_NOT_INITIALISED;
static unsigned int (*sct_random)(void);

#if SVM_SCT_EXACT
/* The published last_events, one bit per event (bit e%8 of byte e/8, image index): the check
 * values of the last step. */
static uint8_t sct_last[SVM_MASK_BYTES];

/* The image index of the file's event `i`. */
static uint8_t file_event(uint8_t i)
{
    return SVM_FLASH_BYTE(&svm_sct_file_events[i]);
}

static uint16_t file_u16(const uint8_t *table, uint16_t at)
{
    return (uint16_t)(SVM_FLASH_BYTE(&table[2u * at]) | (uint16_t)SVM_FLASH_BYTE(&table[2u * at + 1u]) << 8);
}

static uint8_t has_bit(const uint8_t *mask, uint8_t e)
{
    return (uint8_t)(mask[e >> 3] & (1u << (e & 7u)));
}

static void clear_last(void)
{
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        sct_last[i] = 0;
    }
}

/* The published SCT_init and SCT_reset differ in where the states go: SCT_init leaves them as
 * the tables initialise sup_current_state (the file's start states), SCT_reset sets
 * sup_init_state (the image's initial states, where svm_reset puts them). */
static void go_to_file_start(void)
{
    uint8_t s;
    for (s = 0; s < svm_num_supervisors(&sct_vm); s++) {
        sct_vm.state[s] = (svm_state_t)(svm_first_state(&sct_vm, s) + file_u16(svm_sct_file_start, s));
    }
}

/* The published update_input and input buffer: each uncontrollable event's check in file
 * order; those that turned true since the last step go in `rising`. The published VM queues
 * them in a 256-entry ring in this order and drains it in the same order, so a mask walked in
 * file order applies the same events in the same order without the ring. */
static void poll_rising(uint8_t *rising)
{
    uint8_t i, n = svm_num_events(&sct_vm);
    for (i = 0; i < n; i++) {
        uint8_t e = file_event(i), bit = (uint8_t)(1u << (e & 7u));
        const svm_binding_t *b = &sct_bindings[e];
        if (svm_is_controllable(&sct_vm, e)) {
            continue;
        }
        if (b->check == NULL || b->check(b->data) == 0u) {
            sct_last[e >> 3] = (uint8_t)(sct_last[e >> 3] & ~bit);
        } else if (!(sct_last[e >> 3] & bit)) {
            sct_last[e >> 3] |= bit;
            rising[e >> 3] |= bit;
        }
    }
}

/* The `skip`-th event of `mask` counted in file order. */
static uint8_t nth_in_file_order(const uint8_t *mask, unsigned int skip)
{
    uint8_t i, n = svm_num_events(&sct_vm);
    for (i = 0; i < n; i++) {
        uint8_t e = file_event(i);
        if (has_bit(mask, e) && skip-- == 0u) {
            return e;
        }
    }
    return 0xFFu;     /* not reached: skip < the mask's count */
}

/* The published step: inputs in file order, then the draw, on every call. */
static void exact_step(void)
{
    uint8_t rising[SVM_MASK_BYTES] = {0}, enabled[SVM_MASK_BYTES], i, n = svm_num_events(&sct_vm), count;
    poll_rising(rising);
    for (i = 0; i < n; i++) {
        uint8_t e = file_event(i);
        if (has_bit(rising, e)) {
            svm_fire_event(&sct_vm, e);
        }
    }
    count = svm_enabled(&sct_vm, enabled);
    if (count != 0u) {
        unsigned int draw = sct_random != NULL ? sct_random() : (unsigned int)SVM_SCT_RANDOM();
        svm_fire_event(&sct_vm, nth_in_file_order(enabled, draw % count));
    }
}
#endif

svm_vm_t *SCT_vm(void)
{
    return &sct_vm;
}

int SCT_status(void)
{
    return sct_status;
}

int SCT_init(void)
{
    svm_init(&sct_vm);
    svm_set_bindings(&sct_vm, sct_bindings, SVM_MAX_EVENTS);
    sct_status = svm_sct_load(&sct_vm);
#if SVM_SCT_EXACT
    clear_last();
    if (sct_status == SVM_OK) {
        go_to_file_start();
    }
#endif
    return sct_status;
}

void SCT_reset(void)
{
    if (sct_status != SVM_OK) {
        return;
    }
    svm_reset(&sct_vm);
#if SVM_SCT_EXACT
    clear_last();
#endif
}

/* As published, the event's callback, check and data are all replaced (NULL included), which
 * svm_bind does not do (it keeps a binding given NULL, so that an action and a check can be bound
 * separately); and the check of a controllable event is kept out (the published VM never calls
 * it). In exact mode `event` is the file's index. */
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data)
{
    svm_binding_t *b;
    if (sct_status != SVM_OK || event >= svm_num_events(&sct_vm)) {
        return;
    }
#if SVM_SCT_EXACT
    event = file_event(event);
#endif
    b = &sct_bindings[event];
    b->action = clbk;
    b->check = svm_is_controllable(&sct_vm, event) ? (svm_check_fn)NULL : ci;
    b->data = data;
}

void SCT_run_step(void)
{
    if (sct_status != SVM_OK) {
        return;
    }
#if SVM_SCT_EXACT
    exact_step();
#else
    (void)svm_step(&sct_vm);
#endif
}

unsigned long SCT_state(unsigned char sup)
{
    if (sct_status != SVM_OK || sup >= svm_num_supervisors(&sct_vm)) {
        return 0;
    }
#if SVM_SCT_EXACT
    return file_u16(svm_sct_file_states, svm_global_state(&sct_vm, sup));
#else
    return svm_state(&sct_vm, sup);
#endif
}

void SCT_set_random(unsigned int (*random)(void))
{
    sct_random = random;
}
