/* Eva harness over runtime_c/swarmvm_logic_page.c (with swarmvm.c; make prove; docs/proof.md).
 *
 * The CapBot's control-logic flash page: SVM_LOGIC_PAGE_SIZE (4096) bytes of unknown values at
 * the address the build gives (here proof_page, declared by -include logic_page_stub.h), the
 * compiled-in image another PROOF_MAX_IMAGE unknown bytes of an unknown length (the generated
 * tables in the real build: any bytes covers them), and svm_logic_page_load with a map of
 * SVM_MAX_EVENTS entries, as templates/capbot/main.c.j2 declares it; then, if the page was
 * accepted, an unknown number of steps. */
#include "__fc_builtin.h"
#include "swarmvm.h"
#include "swarmvm_logic_page.h"

void Frama_C_show_each_reached(void);

#ifndef PROOF_MAX_IMAGE
#define PROOF_MAX_IMAGE 512
#endif

uint8_t proof_page[SVM_LOGIC_PAGE_SIZE];
static uint8_t compiled[PROOF_MAX_IMAGE];
static uint8_t to_compiled[SVM_MAX_EVENTS];
static svm_vm_t vm;

static uint8_t dispatch(svm_vm_t *v, uint8_t event, uint8_t op)
{
    (void)v;
    (void)event;
    return op == SVM_OP_CHECK ? (uint8_t)Frama_C_interval(0, 1) : 0u;
}

int main(void)
{
    Frama_C_make_unknown((char *)proof_page, sizeof proof_page);
    Frama_C_make_unknown((char *)compiled, sizeof compiled);
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    (void)svm_logic_page_validate();
    if (svm_logic_page_load(&vm, compiled, (uint16_t)Frama_C_interval(0, PROOF_MAX_IMAGE), to_compiled) == SVM_OK) {
        while (Frama_C_nondet(0, 1)) {
            Frama_C_show_each_reached();        /* prove.py: the loop was analysed */
            (void)svm_step(&vm);
        }
    }
    return 0;
}
