/*
 * One event script driving a VM through the Nadzoru C API (SCT_init, SCT_add_callback,
 * SCT_run_step, SCT_reset), built unchanged against the published VM, the published-form VM of
 * benchmarks/published_form/ and swarmvm in exact or canonical mode, so that their logs can be
 * compared line for line (tests/targets/c/test_sct_exact_c.py).
 *
 * SCT_HEADER names the header giving NUM_EVENTS, NUM_SUPERVISORS and the SCT_* prototypes.
 * The states are read through SCT_state() when DRIVER_SCT_STATE is defined (swarmvm), else
 * from the published VM's global sup_current_state.
 *
 * The script is contradictory on purpose: every event's check is a level held for a random
 * number of steps and toggled, so several uncontrollable events rise together and the order in
 * which a VM polls and applies them shows. Its generator is the driver's own (xorshift32), so
 * that rand(), seeded with srand(seed) before SCT_init, is the VM's alone.
 *
 * Log, one line per step: "k: c<ev>... | a<ev>... | s<state>...", the checks called (in call
 * order), the callbacks called (in call order, each an event applied), every supervisor's state.
 * Usage: driver STEPS SEED
 * (exit 1 when SCT_init refused the image, after the run it must not make)
 */
#include <stdio.h>
#include <stdlib.h>

#include SCT_HEADER

#ifdef DRIVER_SCT_STATE
#define STATE(sup) ((unsigned long)SCT_state((unsigned char)(sup)))
#else
extern unsigned long int sup_current_state[];
#define STATE(sup) ((unsigned long)sup_current_state[sup])
#endif

#ifdef DRIVER_SET_RANDOM
/* swarmvm's exact mode given a generator at run time (SCT_set_random); with
 * DRIVER_RESTORE_RANDOM it is taken back (NULL), so the default draws again. */
unsigned int DRIVER_SET_RANDOM(void);
#endif

static unsigned char ids[NUM_EVENTS];
static unsigned char level[NUM_EVENTS];
static unsigned char hold[NUM_EVENTS];
static unsigned long script_state;

static unsigned long next_random(void)
{
    script_state ^= (script_state << 13) & 0xFFFFFFFFul;
    script_state ^= script_state >> 17;
    script_state ^= (script_state << 5) & 0xFFFFFFFFul;
    return script_state & 0xFFFFFFFFul;
}

static unsigned char check(void *data)
{
    unsigned char ev = *(unsigned char *)data;

    printf(" c%u", ev);
    return level[ev];
}

static void action(void *data)
{
    printf(" a%u", *(unsigned char *)data);
}

/* Each event's level is held 1-4 steps then redrawn, true with probability 1/2: on average
 * half the checks are true together, rising at different steps. */
static void advance_script(void)
{
    unsigned ev;

    for (ev = 0; ev < NUM_EVENTS; ev++) {
        if (hold[ev] == 0) {
            level[ev] = (unsigned char)(next_random() & 1u);
            hold[ev] = (unsigned char)(1u + next_random() % 4u);
        }
        hold[ev]--;
    }
}

static void register_all(void)
{
    unsigned ev;

    for (ev = 0; ev < NUM_EVENTS; ev++) {
        ids[ev] = (unsigned char)ev;
        SCT_add_callback((unsigned char)ev, action, check, &ids[ev]);
    }
}

int main(int argc, char **argv)
{
    unsigned long steps, seed, k;
    unsigned sup;
    int refused = 0;

    if (argc != 3)
        return 2;
    steps = strtoul(argv[1], NULL, 10);
    seed = strtoul(argv[2], NULL, 10);
    script_state = seed * 2654435761ul % 0xFFFFFFFFul + 1u;
    srand((unsigned)seed);
#ifdef DRIVER_SCT_STATE
    refused = SCT_init();
    if (refused != 0) {     /* the failed state: the run goes on, and must do nothing */
        printf("SCT_init refused: %d, SCT_status %d\n", refused, SCT_status());
    }
#else
    SCT_init();
#endif
#ifdef DRIVER_SET_RANDOM
    SCT_set_random(DRIVER_SET_RANDOM);
#ifdef DRIVER_RESTORE_RANDOM
    SCT_set_random(NULL);
#endif
#endif
    register_all();
    for (k = 0; k < steps; k++) {
        if (k == steps / 2) {
            SCT_reset();                /* states to the initial ones, edge memory cleared */
            printf("reset\n");
        }
        if (k == steps * 3 / 4) {       /* a NULL registration replaces: event 0 goes silent */
            SCT_add_callback(0, NULL, NULL, NULL);
            printf("unbind 0\n");
        }
        advance_script();
        printf("%lu:", k);
        SCT_run_step();
        printf(" | s");
        for (sup = 0; sup < NUM_SUPERVISORS; sup++)
            printf(" %lu", STATE(sup));
        printf("\n");
    }
    return refused != 0;
}
