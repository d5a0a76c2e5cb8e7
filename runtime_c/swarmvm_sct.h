/*
 * Nadzoru 2 compatible C API over the swarmvm core, so that the published OpenSwarm C, CapBot
 * and Kilobot controllers build unchanged:
 *
 *   SCT_init();                                         load the generated image, reset
 *   SCT_add_callback(EV_x, callback, check, data);      void callback(void *data),
 *                                                       unsigned char check(void *data)
 *   SCT_run_step();  SCT_reset();
 *
 * The generated <name>_tables.h defines EV_x, NUM_EVENTS, NUM_SUPERVISORS and includes this
 * header; the generated <name>_tables.c supplies svm_sct_load() (and, in exact mode, the
 * file-order tables below). Callbacks registered here live in a binding table of
 * SVM_MAX_EVENTS entries inside swarmvm_sct.c (the price of run-time registration; generated
 * compile-time dispatch avoids it); registering an event again replaces its callback, check
 * and data, a NULL included, as the published SCT_add_callback does.
 *
 * Two modes, chosen at compile time by SVM_SCT_EXACT (the same value for every file of a build):
 *   0 (default) canonical: SCT_run_step is svm_step, docs/semantics.md's step with the VM's
 *               options (SCT_vm() gives the VM to set them, or hooks); EV_x are the image's
 *               (canonical, name-order) indices; events processed public-first, as Nadzoru's
 *               SCTPub.
 *   1           exact: SCT_run_step is the published generic C VM's step, bit for bit
 *               (docs/compat.md, "C"): every uncontrollable event's check in the
 *               supervisor file's event order; an event occurs when its check turned true
 *               since the last step; the occurring events applied and called back in file
 *               order; then, on every step, the (SVM_SCT_RANDOM() % n)-th of the n enabled
 *               controllable events in file order. EV_x, NUM_EVENTS and SCT_state() are the
 *               file's numbers, so a published program that indexes its own arrays by EV_x
 *               works unchanged. The VM's options are not used.
 *
 * SCT_init returns SVM_OK or the code svm_load refused the image with (swarmvm_format.h); a VM
 * whose image was refused is in the failed state: SCT_run_step and SCT_reset do nothing,
 * SCT_add_callback registers nothing, SCT_state gives 0, and SCT_status() says why.
 */
#ifndef SWARMVM_SCT_H
#define SWARMVM_SCT_H

#include <stdlib.h>     /* NULL, and rand(): as the published header, which programs rely on */
#include "swarmvm.h"

#ifndef SVM_SCT_EXACT
#define SVM_SCT_EXACT 0
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* SCT_status() before SCT_init: no image was asked for yet. */
#define SCT_NOT_INITIALISED (-1)

int SCT_init(void);
void SCT_reset(void);
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void SCT_run_step(void);

/* SVM_OK once SCT_init loaded the image; else SCT_NOT_INITIALISED or svm_load's SVM_ERR_* code. */
int SCT_status(void);

/* The current state of supervisor `sup`: in exact mode as the supervisor file numbers it (the
 * published sup_current_state[sup]); in canonical mode the image's local number (svm_state). */
unsigned long SCT_state(unsigned char sup);

/* Exact mode's generator: `random` draws the choice instead of SVM_SCT_RANDOM (-DSVM_SCT_RANDOM=
 * rand_soft on the Kilobot; rand by default); NULL restores it. Canonical mode draws from the
 * VM's own generator and ignores this. */
void SCT_set_random(unsigned int (*random)(void));

/* The VM behind the SCT_* functions. */
svm_vm_t *SCT_vm(void);

/* Supplied by the generated tables: load the compiled-in image into `vm`. */
int svm_sct_load(svm_vm_t *vm);

#if SVM_SCT_EXACT
/* Supplied by the generated tables in exact mode (in program memory), the supervisor file's
 * order, which the image (canonical, name order) does not keep:
 *   svm_sct_file_events[i]     the image index of the file's event i (NUM_EVENTS bytes)
 *   svm_sct_file_states[2g..]  the file's number of the image's global state g (u16, low byte
 *                              first), for SCT_state
 *   svm_sct_file_start[2s..]   supervisor s's local state where the file starts it (its
 *                              sup_current_state, u16, low byte first), for SCT_init */
extern const uint8_t svm_sct_file_events[];
extern const uint8_t svm_sct_file_states[];
extern const uint8_t svm_sct_file_start[];

/* The core's one-event transition (swarmvm.c, built with SVM_SCT_EXACT): every supervisor that
 * has `event` follows it (one that cannot counts a violation and stays, as the published VM
 * stays), then the event's action runs. */
void svm_fire_event(svm_vm_t *vm, uint8_t event);
#endif

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_SCT_H */
