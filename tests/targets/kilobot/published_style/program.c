/*
 * A published-style Kilobot program: the energy study's worker, written here from issue 35's
 * description of the published one (which has no licence and is not in the project). One
 * kilolib file, as the published one is: Nadzoru's generic C VM and the supervisor's tables
 * inlined between the two "SCT VM" marker comments, and around them the program: its callbacks
 * registered with SCT_add_callback and dispatched with a switch on the event, its own setup()
 * and loop(), its kilolib message handlers (ARK's configuration, type 10, and its own types 119
 * and 120) and its own message.
 *
 * tests/targets/kilobot/test_published_program.py puts the published-form tables and VM
 * (benchmarks/published_form/) between the markers, which makes the one file a user has, and
 * then moves it over to swarmvm as docs/robots/kilobot.md, "Moving a published program over",
 * says: the section replaced by the generated header's #include, and the states, which the
 * published VM keeps in its global array sup_current_state, read with SCT_state(i).
 *
 * What stands in for the robot's world in the test: the sensors. Bit k of
 * program_script[step] (program_script.h, written by the test: PROGRAM_SCRIPT_STEPS bytes in
 * flash) is the level sensor k reads at that step; bit 6 is ARK's "restart the experiment"
 * (SCT_reset) at that step. After the last step the program stops the CPU (cli; sleep), which
 * ends the simavr run.
 *
 * Log (kilolib's debug.h: printf on USART0, BAUD as built), one line per step:
 *   "<step>:<checks><callbacks> | <state of each supervisor>"
 * the checks as the digits of their events (0-9 in this model), in the order the VM called
 * them; each callback as " <event>", in call order, a moving action adding the turn it drew from
 * rand_soft (L or R); the states as the supervisor file numbers them.
 * Before the first step "goals W C heard H" (the configuration and the neighbours' messages
 * heard before it); "reset" at a restart; "end" last.
 */
#define DEBUG
/* The serial log at 500 kbaud (kilolib's debug.h: 38400 unless BAUD is set): a log line a
 * step at 38400 would take longer to send than the step takes to run. */
#define BAUD 500000
#include <kilolib.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"   /* kilolib's debug.h */
#include <debug.h>
#pragma GCC diagnostic pop

#include "program_script.h"

/* --- SCT VM begin --- */
/* the supervisor's tables and Nadzoru's generic C VM, inlined (put here by the test) */
/* --- SCT VM end --- */

#define CONFIGURATION 10u       /* ARK's configuration message: data[0] the uid (0xFF all), data[1..2] goals */
#define CHARGING_MSG 119u       /* this program's own: "I am charging", data[0] the sender's uid */
#define WORKING_MSG 120u        /* this program's own: "I am working" */
#define ALL_ROBOTS 0xFFu

/* The sensors (bits of program_script[step]); bit 6: ARK restarts the experiment. */
#define SENSE_HIGH_ENERGY 0x01u
#define SENSE_LOW_ENERGY 0x02u
#define SENSE_AT_WORK 0x04u
#define SENSE_AT_CHARGER 0x08u
#define SENSE_NOT_AT_CHARGER 0x10u
#define SENSE_NOT_AT_WORK 0x20u
#define SENSE_RESTART 0x40u

static unsigned char event_ids[NUM_EVENTS];     /* each event's number: the callbacks' data */
static volatile uint8_t goals_set;              /* set by ARK's configuration */
static volatile uint8_t work_goal, charge_goal;
static volatile uint8_t heard;                  /* the neighbours' messages (119, 120) heard */
static volatile uint8_t my_type = WORKING_MSG;  /* what this robot says it does */
static message_t own;
static uint16_t step;
static uint8_t sensed;                          /* this step's sensor levels */
static uint16_t works, charges;

/* A moving action's turn, drawn as the published program draws: kilolib's rand_soft. */
static void random_turn(void)
{
    if (rand_soft() & 1u) {
        set_motors(kilo_turn_left, 0);
        putchar('L');
    } else {
        set_motors(0, kilo_turn_right);
        putchar('R');
    }
}

/* Every event's action: what the VM calls when the event occurs (or is chosen). */
static void callback(void *data)
{
    unsigned char event = *(unsigned char *)data;

    printf(" %u", event);
    switch (event) {
    case EV_moveToWork:
        spinup_motors();
        random_turn();
        my_type = WORKING_MSG;
        break;
    case EV_work:
        set_motors(0, 0);
        set_color(RGB(0, 1, 0));
        works++;
        break;
    case EV_moveToCharge:
        spinup_motors();
        random_turn();
        my_type = CHARGING_MSG;
        break;
    case EV_charge:
        set_motors(0, 0);
        set_color(RGB(0, 0, 1));
        charges++;
        break;
    case EV_lowEnergy:
        set_color(RGB(1, 1, 0));
        break;
    default:
        break;
    }
}

/* Every uncontrollable event's check: whether its sensor reads high now. */
static unsigned char check(void *data)
{
    unsigned char event = *(unsigned char *)data;
    uint8_t bit;

    printf("%u", event);
    switch (event) {
    case EV_highEnergy:
        bit = SENSE_HIGH_ENERGY;
        break;
    case EV_lowEnergy:
        bit = SENSE_LOW_ENERGY;
        break;
    case EV_atWork:
        bit = SENSE_AT_WORK;
        break;
    case EV_atCharger:
        bit = SENSE_AT_CHARGER;
        break;
    case EV_notAtCharger:
        bit = SENSE_NOT_AT_CHARGER;
        break;
    case EV_notAtWork:
        bit = SENSE_NOT_AT_WORK;
        break;
    default:
        bit = 0;
        break;
    }
    return (unsigned char)((sensed & bit) != 0u);
}

static void message_rx(message_t *message, distance_measurement_t *distance)
{
    (void)distance;
    switch (message->type) {
    case CONFIGURATION:
        if (message->data[0] == ALL_ROBOTS || message->data[0] == (uint8_t)kilo_uid) {
            work_goal = message->data[1];
            charge_goal = message->data[2];
            goals_set = 1;
        }
        break;
    case CHARGING_MSG:
    case WORKING_MSG:
        heard++;
        break;
    default:
        break;
    }
}

/* Built here, in kilolib's transmit callback, so that it never changes while it is sent. */
static message_t *message_tx(void)
{
    own.type = my_type;
    own.data[0] = (uint8_t)kilo_uid;
    own.crc = message_crc(&own);
    return &own;
}

static void message_tx_success(void)
{
}

static void setup(void)
{
    unsigned char e;

    debug_init();
    /* The published program seeds from rand_hard(); this one from its uid, so that a run
     * replays and two robots still draw differently. */
    rand_seed((uint8_t)(kilo_uid ^ (kilo_uid >> 8) ^ 0x5Au));
    for (e = 0; e < NUM_EVENTS; e++)
        event_ids[e] = e;
    SCT_init();
    SCT_add_callback(EV_moveToCharge, callback, NULL, &event_ids[EV_moveToCharge]);
    SCT_add_callback(EV_charge, callback, NULL, &event_ids[EV_charge]);
    SCT_add_callback(EV_highEnergy, callback, check, &event_ids[EV_highEnergy]);
    SCT_add_callback(EV_work, callback, NULL, &event_ids[EV_work]);
    SCT_add_callback(EV_moveToWork, callback, NULL, &event_ids[EV_moveToWork]);
    SCT_add_callback(EV_lowEnergy, callback, check, &event_ids[EV_lowEnergy]);
    SCT_add_callback(EV_atWork, callback, check, &event_ids[EV_atWork]);
    SCT_add_callback(EV_atCharger, callback, check, &event_ids[EV_atCharger]);
    SCT_add_callback(EV_notAtCharger, callback, check, &event_ids[EV_notAtCharger]);
    SCT_add_callback(EV_notAtWork, callback, check, &event_ids[EV_notAtWork]);
    set_color(RGB(1, 0, 0));    /* red: waiting for ARK's configuration */
}

static void loop(void)
{
    unsigned char sup;

    if (!goals_set)
        return;                 /* no step before the goals are set */
    if (step == 0u)
        printf("goals %u %u heard %u\n", work_goal, charge_goal, heard);
    if (step == PROGRAM_SCRIPT_STEPS) {
        printf("end %u %u\n", works, charges);
        cli();                  /* done: sleeping with interrupts off stops the CPU */
        sleep_enable();
        sleep_cpu();
    }
    sensed = pgm_read_byte(&program_script[step]);
    if (sensed & SENSE_RESTART) {
        SCT_reset();
        printf("reset\n");
    }
    printf("%u:", step);
    SCT_run_step();
    printf(" |");
    for (sup = 0; sup < NUM_SUPERVISORS; sup++)
        printf(" %lu", (unsigned long)sup_current_state[sup]);
    putchar('\n');
    step++;
}

int main(void)
{
    kilo_init();
    kilo_message_rx = message_rx;
    kilo_message_tx = message_tx;
    kilo_message_tx_success = message_tx_success;
    kilo_start(setup, loop);
    return 0;
}
