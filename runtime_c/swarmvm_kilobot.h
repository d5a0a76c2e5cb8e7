/*
 * swarmvm on the Kilobot (kilolib, ATmega328P): the runtime, a library the program calls.
 *
 * The program keeps kilolib's shape: its own main (kilo_init, the message callbacks,
 * kilo_start(setup, loop)), its setup and loop, its own message handlers. It calls swarmvm:
 *   setup():                  svm_kilobot_begin()         load the image, options, seed
 *   loop():                   svm_kilobot_poll()          one step when due (or svm_kilobot_step)
 *   kilo_message_rx:          svm_kilobot_receive(m, d)   1: the VM's message, taken; 0: yours
 *   kilo_message_tx:          svm_kilobot_transmit()      the VM's message to send, or NULL
 *   kilo_message_tx_success:  svm_kilobot_transmitted()   when the message sent was the VM's
 * The generated {name}_main.c is such a program for new users (setup, loop and callbacks
 * making exactly these calls; the messages the VM does not take reach svm_kilobot_on_message,
 * a weak hook the controller may define); a program
 * with its own main leaves that file out of the build and makes the calls itself. A generated
 * application ({name}_app.c) supplies the tables and glue: the message names
 * (svm_kilobot_wires) and the svm_kilobot_app_* functions below.
 *
 * Step rate: svm_kilobot_poll steps once every SVM_KILOBOT_TICKS_PER_STEP kilolib ticks
 * (default 1). kilo_ticks advances in kilolib's Timer0 compare interrupt, every 256 x 1024
 * cycles at 8 MHz (32.8 ms: 30.5 ticks a second, kilolib's TICKS_PER_SEC rounds it to 31), so by
 * default the VM steps about 30.5 times a second, whatever loop() costs (a step must take under
 * one tick). svm_kilobot_hold(1) makes poll wait (e.g. until the program's goals are set);
 * svm_kilobot_hold(0) lets it step again, at once, then at the same rate.
 *
 * Messages: a controllable public event EV_x broadcasts the message "x" (9 bytes of payload, the
 * name zero-padded, type NORMAL); a received message "x" makes the uncontrollable public event
 * EV__x occur once, at the next step (several copies before that step count once). kilolib
 * offers one message per transmission slot (kilo_tx_period, default 3906 Timer0 counts, about
 * 0.5 s): events fired faster wait their turn, one message per event, taken in turn. Every
 * other message (any other type, such as ARK's configuration messages of type 10 or a
 * program's own types; a NORMAL one that names no received event) is the program's:
 * svm_kilobot_receive returns 0 for it.
 *
 * Seeds: each robot's VM draws from its own seed, SVM_KILOBOT_UID_SEED(kilo_uid) by default:
 * the same robot gets the same seed on every run (a run can be replayed), two robots get two.
 * -DSVM_KILOBOT_SEED=SVM_KILOBOT_SEED_RAND_HARD seeds from kilolib's rand_hard() instead (a new
 * seed each run, as the published Kilobot program seeds its generator); svm_kilobot_set_options
 * sets any seed from the program's code.
 *
 * Interrupts: kilolib calls the receive callback from its IR interrupt and the transmit callbacks
 * from its Timer0 interrupt. Every variable they share with loop() is volatile and loop() reads
 * or clears it inside ATOMIC_BLOCK(ATOMIC_RESTORESTATE) (util/atomic.h), each block a few
 * instructions so that the IR receiver's bit timing keeps its margin. The message kilolib sends
 * is built inside its own transmit callback, so it never changes while kilolib sends it.
 *
 * EEPROM: only a build with SVM_LEARNED writes EEPROM: its learned parameters, from
 * SVM_KILOBOT_EEPROM_FREE up (swarmvm_kilobot_eeprom.h), clear of kilolib's calibration.
 *
 * Learning (SVM_LEARNED, `make LEARNED=1`): the learned selection policy (docs/learning.md)
 * chooses among the enabled controllable events, seeded with the robot's seed; the controller
 * credits each choice with svm_kilobot_reward(). The parameters are kept across resets and power
 * cuts in the EEPROM's two-slot store (swarmvm_learn_store.h): svm_kilobot_begin loads the newest
 * valid record (initial parameters, all preferences 0, when there is none), and a reward saves
 * them every SVM_KILOBOT_KEEP_EVERY rewards when they moved by SVL_KEEPER_EPSILON (1.0) or more
 * since the last save (swarmvm_learn_store.h; the policy's settings are its SVL_KEEPER_*). Default 1024: at one reward per step (30.5 a second) at most a save
 * every 34 s; each byte of the two slots is then written at most every 67 s, and the EEPROM's
 * 100,000 writes per byte last over 77 days of continuous learning. A save blocks loop() for
 * about 3.3 ms per byte written (the kilolib interrupts keep running). Not with SVM_STREAM
 * (a streamed image would change the parameters' shape).
 */
#ifndef SWARMVM_KILOBOT_H
#define SWARMVM_KILOBOT_H

#include <stdint.h>
#include "kilolib.h"
#include "swarmvm.h"
#include "swarmvm_kilobot_eeprom.h"
#include "swarmvm_stream.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef SVM_KILOBOT_TICKS_PER_STEP
#define SVM_KILOBOT_TICKS_PER_STEP 1u
#endif

/* The options svm_kilobot_begin sets (docs/semantics.md; swarmvm.h's SVM_INPUTS_*,
 * SVM_CONTROL_*, SVM_POLICY_*): canonical by default. */
#ifndef SVM_KILOBOT_OPTIONS
#define SVM_KILOBOT_OPTIONS 0u
#endif

/* Where svm_kilobot_begin takes the seed from (SVM_KILOBOT_SEED): the robot's kilo_uid
 * (default), or kilolib's rand_hard() (four bytes of ADC noise: a new seed on every start). */
#define SVM_KILOBOT_SEED_UID 0
#define SVM_KILOBOT_SEED_RAND_HARD 1
#ifndef SVM_KILOBOT_SEED
#define SVM_KILOBOT_SEED SVM_KILOBOT_SEED_UID
#endif

/* The seed of the robot whose kilo_uid is `uid`: the uid in the top 16 bits, its complement in
 * the bottom 16. Distinct for every uid and never 0 (a half is 0 only when the other is 0xFFFF),
 * so kilo_uid 0 never meets xorshift's fixed point; both halves differ between two robots, where
 * seeds such as 1 and 2 would start the generator on near multiples of each other. Two bytes
 * moved, no multiplication. swarmvm.targets.kilobot.uid_seed is the same formula, to replay a
 * robot's run. */
#define SVM_KILOBOT_UID_SEED(uid) (((uint32_t)(uint16_t)(uid) << 16) | (uint16_t)~(uint16_t)(uid))

/* kilolib message type of an image chunk: data = [sequence number, 8 image bytes]. It lies
 * clear of kilolib's own types (NORMAL 0, GPS 1, and the system types from 0x80 up, which
 * kilolib handles itself), so chunks reach kilo_message_rx next to the NORMAL messages that
 * carry public events. Only a build with SVM_STREAM receives chunks; others ignore them. */
#define SVM_MSG_IMAGE_CHUNK 0x53u

/* SVM_STREAM (build flag, default off): receive a new image over messages and swap it in
 * between two steps. SVM_STREAM_BYTES: the receive buffer (RAM), the largest image accepted.
 * The default, 512 B, takes every corpus model but network_worker and leaves over 1 KB of the
 * Kilobot's 2 KB of RAM to the stack. SVM_KILOBOT_CHUNK_SLOTS chunks may arrive between two
 * steps (more are dropped: the reception then stops at a gap); at kilolib's message rate (one
 * per sender every 0.5 s) two is plenty. SVM_KILOBOT_NAME_BYTES: room for the longest event
 * name a streamed image may use, plus 2. */
#ifndef SVM_STREAM
#define SVM_STREAM 0
#endif
#ifndef SVM_STREAM_BYTES
#define SVM_STREAM_BYTES 512u
#endif
#ifndef SVM_KILOBOT_CHUNK_SLOTS
#define SVM_KILOBOT_CHUNK_SLOTS 2u
#endif
#ifndef SVM_KILOBOT_NAME_BYTES
#define SVM_KILOBOT_NAME_BYTES 34u
#endif

#ifndef SVM_LEARNED
#define SVM_LEARNED 0
#endif
#if SVM_LEARNED
#include "swarmvm_learn_store.h"
/* Room for the preferences: states x controllable events of the model (at most). */
#ifndef SVM_KILOBOT_THETA
#define SVM_KILOBOT_THETA (SVM_MAX_STATES * SVM_MAX_EVENTS)
#endif
#ifndef SVM_KILOBOT_KEEP_EVERY
#define SVM_KILOBOT_KEEP_EVERY 1024u
#endif
/* Each of the two EEPROM slots (from SVM_KILOBOT_EEPROM_FREE; the ATmega328P has 1 KB). */
#define SVM_KILOBOT_SLOT_BYTES SVM_STORE_SLOT_BYTES(SVL_KEEPER_RECORD_BYTES(SVM_KILOBOT_THETA), 1u)
#if SVM_STREAM
#error "SVM_LEARNED with SVM_STREAM: a streamed image would change the learned parameters' shape"
#endif

/* Credit the last choice of the learned policy with a Q16 reward (SVL_Q16(x)); saves the
 * parameters to EEPROM on the cadence above. Call it from loop() context (an action, a check,
 * svm_kilobot_after_step), never from an interrupt. */
void svm_kilobot_reward(int32_t reward_q16);

/* The learned policy and its keeper (saves done since the start), to inspect. */
const svl_keeper_t *svm_kilobot_keeper(void);
#endif

/* One public event and the message that carries it (in program memory). */
typedef struct {
    uint8_t event;          /* the program's event index; SVM_KILOBOT_END ends the table */
    uint8_t received;       /* 1: a message received makes it occur; 0: firing it sends one */
    char wire[9];           /* the message payload: the name, zero-padded */
} svm_kilobot_wire_t;

#define SVM_KILOBOT_END 0xFFu

/* Supplied by the generated application ({name}_app.c): */
extern const svm_kilobot_wire_t svm_kilobot_wires[];            /* ends with SVM_KILOBOT_END */
int svm_kilobot_app_load(svm_vm_t *vm);                         /* svm_load_P of the image */
uint8_t svm_kilobot_app_dispatch(svm_vm_t *vm, uint8_t event, uint8_t op);
void svm_kilobot_app_on_stream(uint8_t status, uint16_t value); /* the controller's hook */

/* ---- what the program calls ------------------------------------------------------------ */

/* From the program's setup() (kilolib runs it once kilo_start has the RUN message): loads the
 * compiled-in image with SVM_KILOBOT_OPTIONS and the robot's seed (SVM_KILOBOT_SEED; kilolib's
 * rand_soft is seeded with the seed's low byte too, for the Nadzoru C API's draw), starts the
 * step clock, then calls svm_kilobot_on_begin. Returns SVM_OK, or the SVM_ERR_* code of the
 * refused image (the VM then holds no image and its steps fire nothing; the generated setup
 * lights the LED red), or -1 when the learned policy does not fit (SVM_LEARNED). */
int svm_kilobot_begin(void);

/* From loop(): one svm_kilobot_step when SVM_KILOBOT_TICKS_PER_STEP ticks passed since the last
 * and the program does not hold the VM (svm_kilobot_hold); else nothing. */
void svm_kilobot_poll(void);

/* One step now, whatever the clock and the hold (a program that times its own steps calls this
 * instead of svm_kilobot_poll): takes the image chunks that came (SVM_STREAM), steps the VM,
 * then calls svm_kilobot_after_step. Returns the number of events fired. */
uint8_t svm_kilobot_step(void);

/* 1: svm_kilobot_poll does not step until svm_kilobot_hold(0) (the step clock waits; messages
 * received meanwhile count once, at the first step after). May be called before
 * svm_kilobot_begin (to start held) and from the message callbacks. */
void svm_kilobot_hold(uint8_t hold);

/* From kilo_message_rx (the IR interrupt; the program's own handler calls it first, or only for
 * the types it does not handle): 1 when `message` is the VM's (a NORMAL message naming one of
 * its received public events; an image chunk, SVM_MSG_IMAGE_CHUNK, with SVM_STREAM), which it
 * took; 0 when it is the program's, after giving it to svm_kilobot_on_message. */
uint8_t svm_kilobot_receive(message_t *message, distance_measurement_t *distance);

/* From kilo_message_tx (the Timer0 interrupt): the message of the next public event waiting to
 * go, built now, or NULL when none waits: the program may send its own in that slot (or in any
 * slot: the VM's message then waits for a later one). */
message_t *svm_kilobot_transmit(void);

/* From kilo_message_tx_success, when the message kilolib sent is the one svm_kilobot_transmit
 * returned in that same callback: that event's message went out. */
void svm_kilobot_transmitted(void);

/* Options (SVM_INPUTS_* | SVM_CONTROL_* | SVM_POLICY_*) and seed from the program's code, e.g.
 * from svm_kilobot_on_begin or after svm_kilobot_begin in its own setup. After the begin it
 * also resets the VM (initial states, generator re-seeded: swarmvm.h's svm_reset), so call it
 * before the first step unless a restart is meant. Seeds kilolib's rand_soft as begin does. */
void svm_kilobot_set_options(uint8_t options, uint32_t seed);

/* The VM (svm_state, svm_violations, svm_event_name, and any svm_* call between two steps). */
svm_vm_t *svm_kilobot_vm(void);

/* ---- hooks: weak and empty in the runtime, a program may define its own ----------------- */

/* Called at the end of svm_kilobot_begin: the place, for a program built with the generated
 * {name}_main.c, to call svm_kilobot_set_options or svm_kilobot_hold. */
void svm_kilobot_on_begin(void);

/* Called after each step, in loop() (e.g. to print a trace line). */
void svm_kilobot_after_step(void);

/* Called by svm_kilobot_receive, in the IR interrupt, with every message it does not take
 * (ARK's type 10, a program's own types...): how a program built with the generated
 * {name}_main.c gets them (a program with its own handler has them already). Keep it short:
 * copy what is needed and return. */
void svm_kilobot_on_message(message_t *message, distance_measurement_t *distance);

/* ---- what the generated glue calls ------------------------------------------------------ */

/* Queue the message of the controllable public event `event` (called by the dispatch). */
void svm_kilobot_send(uint8_t event);

/* Whether a message for the uncontrollable public event `event` came since its last check;
 * the check forgets it (the generated check of EV__x calls this). */
unsigned char svm_kilobot_take(uint8_t event);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_KILOBOT_H */
