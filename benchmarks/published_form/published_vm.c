/*
 * The published generic C VM of Nadzoru (the one the CapBot's lib/sct/src/<name>.c and the
 * Kilobot energy-study program carry), written here from its description in issue 35 so that
 * swarmvm can be compared with it: an oracle for the tests (tests/targets/c/test_sct_exact_c.py)
 * and the baseline of the benchmarks. It is not swarmvm code and is not optimised: it keeps the
 * published data layout and its RAM (the 256-entry input ring, last_events, the callback table)
 * because what is measured or compared is the published VM, not a better one.
 *
 * Build: the tables come from the file named by SCT_TABLES, in the published form (the
 * `#define EV_x n`, NUM_EVENTS, NUM_SUPERVISORS and the six arrays inside `#if FN_SUP`), e.g.
 *     cc -c published_vm.c -DSCT_TABLES='"model_tables.c"'
 * RANDOM() is rand() unless -DSCT_RANDOM=fn names another generator (kilolib's rand_soft;
 * -DSCT_RANDOM_TYPE=t if it returns other than unsigned char).
 *
 * One step (SCT_run_step), on every call, inputs or not:
 *   1. every uncontrollable event's check, in file (index) order; a rising edge queues the event;
 *   2. the queue drained: each event moves every supervisor that has it, then its callback runs;
 *   3. the enabled controllable events counted (n); if n > 0 the (RANDOM() % n)-th of them in
 *      index order moves the supervisors and its callback runs. The published source tests
 *      "input buffer empty" here only in a comment, so the choice follows the inputs every time.
 */
#include <stdlib.h>

#ifndef SCT_TABLES
#error "define SCT_TABLES as the quoted name of the tables file, e.g. -DSCT_TABLES='\"model_tables.c\"'"
#endif

#define FN_SUP 1
#include SCT_TABLES

#ifndef SCT_RANDOM
#define SCT_RANDOM rand
#else
/* A generator given by name is declared here, so that no header of its library is needed:
 * SCT_RANDOM_TYPE is its return type (unsigned char, as kilolib's uint8_t rand_soft(), unless
 * given); only its value, promoted to an integer, is used. */
#ifndef SCT_RANDOM_TYPE
#define SCT_RANDOM_TYPE unsigned char
#endif
SCT_RANDOM_TYPE SCT_RANDOM(void);
#endif

#define TRANSITION_BYTES 3u    /* event, target state high byte, low byte */
#define INPUT_RING 256u        /* the published queue; its uint8 pointers wrap at 256 */

void SCT_init(void);
void SCT_reset(void);
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void SCT_run_step(void);

struct registration {
    void (*action)(void *);
    unsigned char (*check)(void *);
    void *data;
};

static struct registration registered[NUM_EVENTS];
static unsigned char last_events[NUM_EVENTS];
static unsigned char input_ring[INPUT_RING];
static unsigned char ring_put = 0;     /* uint8: the published pointers, wrapping with the ring */
static unsigned char ring_take = 0;

/* Where state `state` of supervisor `sup` starts in sup_data: the rows are of variable length
 * (a count, then three bytes per transition), so the published layout is walked row by row. */
static unsigned long int state_row(unsigned char sup, unsigned long int state)
{
    unsigned long int at = sup_data_pos[sup];
    unsigned long int walked;

    for (walked = 0; walked < state; walked++)
        at += 1u + TRANSITION_BYTES * (unsigned long int)sup_data[at];
    return at;
}

/* Every supervisor whose alphabet has `event` follows its transition on it from the current
 * state; a supervisor with no such transition stays where it is (the published behaviour). */
static void apply_event(unsigned char event)
{
    unsigned char sup;

    for (sup = 0; sup < NUM_SUPERVISORS; sup++) {
        unsigned long int at;
        unsigned char left;

        if (!sup_events[sup][event])
            continue;
        at = state_row(sup, sup_current_state[sup]);
        for (left = sup_data[at++]; left > 0; left--, at += TRANSITION_BYTES) {
            if (sup_data[at] == event) {
                sup_current_state[sup] = (unsigned long int)sup_data[at + 1] * 256u + sup_data[at + 2];
                break;
            }
        }
    }
}

static void run_callback(unsigned char event)
{
    if (registered[event].action != NULL)
        registered[event].action(registered[event].data);
}

/* Step 1: poll in index order; queue only a check that turned true since the last poll. */
static void poll_inputs(void)
{
    unsigned char ev;

    for (ev = 0; ev < NUM_EVENTS; ev++) {
        unsigned char high;

        if (ev_controllable[ev])
            continue;
        high = registered[ev].check != NULL ? registered[ev].check(registered[ev].data) : 0;
        if (!high) {
            last_events[ev] = 0;
        } else if (!last_events[ev]) {
            input_ring[ring_put++] = ev;
            last_events[ev] = 1;
        }
    }
}

/* Step 2: the queued events in the order they were queued, each applied then called back. */
static void drain_inputs(void)
{
    while (ring_take != ring_put) {
        unsigned char ev = input_ring[ring_take++];

        apply_event(ev);
        run_callback(ev);
    }
}

/* Whether supervisor `sup`, in its current state, has a transition on `event`. */
static int has_transition(unsigned char sup, unsigned char event)
{
    unsigned long int at = state_row(sup, sup_current_state[sup]);
    unsigned char left;

    for (left = sup_data[at++]; left > 0; left--, at += TRANSITION_BYTES)
        if (sup_data[at] == event)
            return 1;
    return 0;
}

/* Controllable, and not disabled by any supervisor that has it in its alphabet. */
static int enabled(unsigned char event)
{
    unsigned char sup;

    if (!ev_controllable[event])
        return 0;
    for (sup = 0; sup < NUM_SUPERVISORS; sup++)
        if (sup_events[sup][event] && !has_transition(sup, event))
            return 0;
    return 1;
}

/* Step 3: the (RANDOM() % n)-th enabled controllable event in index order, if any. */
static void choose_controllable(void)
{
    unsigned char on[NUM_EVENTS];
    unsigned char ev, count = 0;
    unsigned long int skip;

    for (ev = 0; ev < NUM_EVENTS; ev++) {
        on[ev] = (unsigned char)enabled(ev);
        count = (unsigned char)(count + on[ev]);
    }
    if (count == 0)
        return;
    skip = (unsigned long int)(SCT_RANDOM() % count);
    for (ev = 0; ev < NUM_EVENTS; ev++) {
        if (!on[ev])
            continue;
        if (skip-- == 0) {
            apply_event(ev);
            run_callback(ev);
            return;
        }
    }
}

/* As published: the registrations and the edge memory are cleared; the states are not (they
 * start as the tables' sup_current_state). */
void SCT_init(void)
{
    unsigned char ev;

    for (ev = 0; ev < NUM_EVENTS; ev++) {
        last_events[ev] = 0;
        registered[ev].action = NULL;
        registered[ev].check = NULL;
        registered[ev].data = NULL;
    }
}

void SCT_reset(void)
{
    unsigned char i;

    for (i = 0; i < NUM_SUPERVISORS; i++)
        sup_current_state[i] = sup_init_state[i];
    for (i = 0; i < NUM_EVENTS; i++)
        last_events[i] = 0;
}

/* All three replaced, NULLs included. */
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data)
{
    registered[event].action = clbk;
    registered[event].check = ci;
    registered[event].data = data;
}

void SCT_run_step(void)
{
    poll_inputs();
    drain_inputs();
    choose_controllable();
}
