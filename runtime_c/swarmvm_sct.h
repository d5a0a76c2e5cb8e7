/*
 * Nadzoru 2 compatible C API over the swarmvm core, so that the published OpenSwarm C and
 * Kilobot controllers build unchanged:
 *
 *   SCT_init();                                         load the generated image, reset
 *   SCT_add_callback(EV_x, callback, check, data);      void callback(void *data),
 *                                                       unsigned char check(void *data)
 *   SCT_run_step();  SCT_reset();
 *
 * The generated <name>_tables.h defines EV_x, NUM_EVENTS, NUM_SUPERVISORS and includes this
 * header; the generated <name>_tables.c supplies svm_sct_load(). Callbacks registered here
 * live in a binding table of SVM_MAX_EVENTS entries inside swarmvm_sct.c (the price of
 * run-time registration; generated compile-time dispatch avoids it). Events are processed
 * public-first, as Nadzoru's SCTPub does. SCT_vm() gives the VM to set options
 * (svm_set_options) or hooks; the defaults are docs/semantics.md's.
 */
#ifndef SWARMVM_SCT_H
#define SWARMVM_SCT_H

#include "swarmvm.h"

#ifdef __cplusplus
extern "C" {
#endif

void SCT_init(void);
void SCT_reset(void);
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void SCT_run_step(void);

/* The VM behind the SCT_* functions. */
svm_vm_t *SCT_vm(void);

/* Supplied by the generated tables: load the compiled-in image into `vm`. */
int svm_sct_load(svm_vm_t *vm);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_SCT_H */
