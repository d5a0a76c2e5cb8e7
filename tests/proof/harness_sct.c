/* Eva harness over runtime_c/swarmvm_sct.c, the Nadzoru 2 C API (with swarmvm.c; make prove;
 * docs/proof.md).
 *
 * svm_sct_load, which the generated {name}_tables.c supplies: in canonical mode (SVM_SCT_EXACT=0,
 * the sct configuration) svm_load_P of PROOF_MAX_IMAGE unknown bytes of an unknown length, as in
 * harness_core.c (any tables.c, one edited by hand included); in exact mode (SVM_SCT_EXACT=1,
 * sct-exact) the configuration's model's image and the supervisor file's order tables
 * (proof_image.h, which prove.py writes from the model as the generated tables.c holds them:
 * exact mode runs only the image those tables were written with). Then SCT_init, and a loop of an
 * unknown number of iterations (Eva widens it), each doing any of: SCT_add_callback of any event
 * number (0 .. 255) with a callback or NULL and a check answering an unknown 0 or 1 or NULL;
 * SCT_set_random with a generator of unknown values or NULL (exact mode's draw; otherwise
 * SVM_SCT_RANDOM, here kilolib's rand_soft as on the Kilobot, an unknown byte); SCT_run_step;
 * SCT_reset; SCT_state of any supervisor number; SCT_init again. The callbacks only answer
 * (they call no SCT_* function during a step). */
#include "__fc_builtin.h"
#include "swarmvm_sct.h"
#if SVM_SCT_EXACT
#include "proof_image.h"
#endif

void Frama_C_show_each_reached(void);

#ifndef PROOF_MAX_IMAGE
#define PROOF_MAX_IMAGE 512
#endif

#if SVM_SCT_EXACT
int svm_sct_load(svm_vm_t *vm)
{
    return svm_load_P(vm, proof_image, sizeof proof_image);
}

uint8_t rand_soft(void)
{
    return (uint8_t)Frama_C_interval(0, 255);
}
#else
static uint8_t unknown_image[PROOF_MAX_IMAGE];
static uint16_t unknown_length;

int svm_sct_load(svm_vm_t *vm)
{
    return svm_load_P(vm, unknown_image, unknown_length);
}
#endif

static unsigned int draw(void)
{
    return Frama_C_unsigned_int_interval(0, 0xFFFFu);    /* rand's range where int has 16 bits */
}

static void callback(void *data)
{
    (void)data;
}

static unsigned char check(void *data)
{
    (void)data;
    return (unsigned char)Frama_C_interval(0, 1);
}

int main(void)
{
#if !SVM_SCT_EXACT
    unknown_length = (uint16_t)Frama_C_interval(0, PROOF_MAX_IMAGE);
    Frama_C_make_unknown((char *)unknown_image, PROOF_MAX_IMAGE);
#endif
    (void)SCT_init();
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        if (Frama_C_nondet(0, 1)) {
            SCT_add_callback((unsigned char)Frama_C_interval(0, 255), Frama_C_nondet(0, 1) ? callback : NULL,
                             Frama_C_nondet(0, 1) ? check : NULL, NULL);
        }
        if (Frama_C_nondet(0, 1)) {
            SCT_set_random(Frama_C_nondet(0, 1) ? draw : NULL);
        }
        SCT_run_step();
        if (Frama_C_nondet(0, 1)) {
            SCT_reset();
        }
        (void)SCT_state((unsigned char)Frama_C_interval(0, 255));
        if (Frama_C_nondet(0, 1)) {
            (void)SCT_init();
        }
    }
    return 0;
}
