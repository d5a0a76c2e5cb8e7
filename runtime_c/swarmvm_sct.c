/* Nadzoru 2 compatible C API (see swarmvm_sct.h): a thin layer over one swarmvm VM. */
#include "swarmvm_sct.h"

static svm_vm_t sct_vm;
static svm_binding_t sct_bindings[SVM_MAX_EVENTS];

svm_vm_t *SCT_vm(void)
{
    return &sct_vm;
}

void SCT_init(void)
{
    svm_init(&sct_vm);
    svm_set_bindings(&sct_vm, sct_bindings, SVM_MAX_EVENTS);
    (void)svm_sct_load(&sct_vm);
}

void SCT_reset(void)
{
    svm_reset(&sct_vm);
}

/* As in Nadzoru, the check of a controllable event is ignored. */
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data)
{
    (void)svm_bind(&sct_vm, event, clbk, svm_is_controllable(&sct_vm, event) ? (svm_check_fn)0 : ci, data);
}

void SCT_run_step(void)
{
    (void)svm_step(&sct_vm);
}
