/*
 * swarmvm on the Kilobot (kilolib, ATmega328P): the application runtime.
 *
 * swarmvm_kilobot.c runs one VM as a kilolib program: kilo_start's setup() loads the image,
 * loop() steps the VM at a fixed rate, and kilolib's message callbacks carry public events (and,
 * with SVM_STREAM, new images). A generated application ({name}_app.c) supplies only tables and
 * glue: the message names (svm_kilobot_wires) and the four svm_kilobot_app_* functions below.
 *
 * Step rate: the VM steps once every SVM_KILOBOT_TICKS_PER_STEP kilolib ticks (default 1).
 * kilo_ticks advances in kilolib's Timer0 compare interrupt, every 256 x 1024 cycles at 8 MHz
 * (32.8 ms: 30.5 ticks a second, kilolib's TICKS_PER_SEC rounds it to 31), so by default the VM
 * steps about 30.5 times a second, whatever loop() costs (a step must take under one tick).
 *
 * Messages: a controllable public event EV_x broadcasts the message "x" (9 bytes of payload, the
 * name zero-padded, type NORMAL); a received message "x" makes the uncontrollable public event
 * EV__x occur once, at the next step (several copies before that step count once). kilolib
 * offers one message per transmission slot (kilo_tx_period, default 3906 Timer0 counts, about
 * 0.5 s): events fired faster wait their turn, one message per event, taken in turn.
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
 * chooses among the enabled controllable events, seeded with kilo_uid; the controller credits
 * each choice with svm_kilobot_reward(). The parameters are kept across resets and power cuts
 * in the EEPROM's two-slot store (swarmvm_learn_store.h): setup() loads the newest valid
 * record (initial parameters, all preferences 0, when there is none), and a reward saves them
 * every SVM_KILOBOT_KEEP_EVERY rewards when they moved by SVL_KEEPER_EPSILON (1.0) or more
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

/* kilo_init, the message callbacks, kilo_start: never returns. */
void svm_kilobot_run(void);

/* The VM, for the controller to inspect (svm_state, svm_violations, svm_event_name). */
const svm_vm_t *svm_kilobot_vm(void);

/* Queue the message of the controllable public event `event` (called by the dispatch). */
void svm_kilobot_send(uint8_t event);

/* Whether a message for the uncontrollable public event `event` came since its last check;
 * the check forgets it (the generated check of EV__x calls this). */
unsigned char svm_kilobot_take(uint8_t event);

/* Called after each step, in loop(). The runtime's definition is weak and empty: a program may
 * define its own (e.g. to print a trace line). */
void svm_kilobot_after_step(void);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_KILOBOT_H */
