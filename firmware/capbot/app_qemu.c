/*
 * Bare-metal main of a generated CapBot application, for QEMU mps2-an386: the tables, dispatch
 * and controller that run on the robot (src/ of `swarmvm gen --target capbot`, everything but
 * the Zephyr main.c), stepped SVM_APP_STEPS times without Zephyr, with the default options and
 * seed, printing the canonical trace (docs/conformance.md) through semihosting.
 *
 * QEMU has no world to sense, so this main plays the environment: at each step every
 * uncontrollable event, in event order, occurs with probability 1/4 (xorshift32 seeded with
 * ENV_SEED, index mapping of docs/semantics.md: below(4) == 0), on top of what the controller's
 * own check says. The same draw in Python gives the event script of the reference trace.
 *
 * The logic runs from the control-logic flash page when it holds a valid image (swarmvm_logic_page.h):
 * the compiled-in image is loaded first, then swapped for the page's. A blank page (every byte
 * 0xFF as erased flash, or 0x00 as QEMU's unloaded memory) is the expected state of a robot
 * given no page yet and is reported as such; any other refused page is reported on stderr with
 * its SVM_ERR_* code. Either way the compiled-in logic runs. The controller's
 * actions and checks are matched to the page image's events by name (events it does not
 * know get no action and a check that returns 0).
 *
 * Built with the minimal profile (-DSVM_TRUSTED_IMAGE=<model name>_image: the generated
 * qemu/Makefile's MINIMAL=1), only the compiled-in image can run (svm_load_P refuses any other),
 * so there is no flash page to read: the compiled-in logic runs, stderr says so.
 *
 * The model comes from svm_app.h, which gen writes into the project's qemu/ folder
 * (templates/capbot/svm_app.h.j2): its tables header and its image, load and dispatch by name, so
 * that a model named like a macro (NULL, EOF, stdout) builds as well as any other. Build with
 * that folder and src/ on the include path and the model's limit flags (or page_limits.flags),
 * as qemu/Makefile does; the CapBot API comes from capbot.h / capbot_qemu.c (stand-ins). This
 * file's own identifiers that a model's could take (<model>_dispatch) start with svm_app_: no
 * model name starts with svm.
 */
#include <stdio.h>

#include "capbot.h"
#include "swarmvm_logic_page.h"
#include "swarmvm_trace.h"
#include "svm_app.h"

#ifndef SVM_APP_STEPS
#define SVM_APP_STEPS 20
#endif

#define ENV_SEED 2024u

static svm_vm_t vm;
static uint8_t to_compiled[SVM_MAX_EVENTS]; /* running image's event -> controller's event */
static uint8_t fired[SVM_MAX_EVENTS + 1];
static uint8_t num_fired;

static uint32_t env_rng = ENV_SEED;
static uint8_t occurs[SVM_MASK_BYTES];

static uint32_t env_next(void)
{
    env_rng ^= env_rng << 13;
    env_rng ^= env_rng >> 17;
    env_rng ^= env_rng << 5;
    return env_rng;
}

/* This step's environment: which uncontrollable events occur whatever the checks say. */
static void draw_environment(void)
{
    uint8_t e;
    for (e = 0; e < svm_num_events(&vm); e++) {
        uint8_t bit = (uint8_t)(1u << (e & 7u));
        occurs[e >> 3] = (uint8_t)(occurs[e >> 3] & ~bit);
        if (!svm_is_controllable(&vm, e) && ((env_next() >> 16) * 4u >> 16) == 0u) {
            occurs[e >> 3] = (uint8_t)(occurs[e >> 3] | bit);
        }
    }
}

/* The generated dispatch, with the environment added to the checks and each action noted:
 * the events fired in this step. */
static uint8_t svm_app_traced_dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    uint8_t own = to_compiled[event];
    uint8_t result = own == SVM_LOGIC_NO_EVENT ? 0u : SVM_APP_DISPATCH(machine, own, op);
    if (op == SVM_OP_CHECK) {
        return (uint8_t)(result || ((occurs[event >> 3] >> (event & 7u)) & 1u));
    }
    if (num_fired < sizeof fired) {
        fired[num_fired++] = event;
    }
    return result;
}

static void to_stdout(char c)
{
    (void)putchar(c);
}

static void to_stderr(char c)
{
    (void)fputc(c, stderr);
}

static void put_trace_line(unsigned long step)
{
    svm_put_trace_line(to_stdout, &vm, (uint32_t)step, fired, num_fired);
    (void)putchar('\n');
}

#ifndef SVM_TRUSTED_IMAGE
/* A page of one repeated byte, 0xFF (erased flash) or 0x00 (memory QEMU was given nothing for),
 * has never been written: saying "blank" there, not "refused", keeps the expected state of a
 * robot without a page from reading like a fault. */
static int logic_page_is_blank(void)
{
    const uint8_t *page = svm_logic_page();
    uint16_t i;
    if (page[0] != 0xFFu && page[0] != 0x00u) {
        return 0;
    }
    for (i = 1; i < svm_logic_page_size(); i++) {
        if (page[i] != page[0]) {
            return 0;
        }
    }
    return 1;
}
#endif

/* Compiled-in logic first, then the flash page's if it holds a valid image (in the minimal
 * profile, the compiled-in logic alone, its events the controller's own). A refused
 * compiled-in image (corrupted: SVM_ERR_CRC) is reported and nothing runs, as on the robot. */
static int load_logic(void)
{
    int page = SVM_APP_LOAD(&vm);
    if (page != SVM_OK) {
        (void)fputs("compiled-in " SVM_APP_NAME ": refused (swarmvm error ", stderr);
        svm_put_decimal(to_stderr, (uint32_t)page);
        (void)fputs(")\n", stderr);
        return 0;
    }
#ifdef SVM_TRUSTED_IMAGE
    for (page = 0; page < SVM_MAX_EVENTS; page++) {
        to_compiled[page] = (uint8_t)page;
    }
    (void)fputs("minimal profile: running the compiled-in " SVM_APP_NAME " (no logic page)\n", stderr);
#else
    page = svm_logic_page_load(&vm, SVM_APP_IMAGE, (uint16_t)sizeof SVM_APP_IMAGE, to_compiled);
    /* fputs, not fprintf: printf's formatter would triple the application's flash. */
    if (page == SVM_OK) {
        (void)fputs("logic page: running its image\n", stderr);
    } else if (logic_page_is_blank()) {
        (void)fputs("logic page: blank (never written), running the compiled-in " SVM_APP_NAME "\n", stderr);
    } else {
        (void)fputs("logic page: not a valid image, refused (swarmvm error ", stderr);
        svm_put_decimal(to_stderr, (uint32_t)page);
        (void)fputs("), running the compiled-in " SVM_APP_NAME "\n", stderr);
    }
#endif
    return 1;
}

int main(void)
{
    unsigned long step;
    int err = cb_led_init() | cb_btn_init() | cb_measure_init() | cb_motor_init();
    if (err) {
        return 2;
    }
    svm_init(&vm);
    svm_set_dispatch(&vm, svm_app_traced_dispatch);
    if (!load_logic()) {
        return 1;
    }
    for (step = 1; step <= SVM_APP_STEPS; step++) {
        num_fired = 0;
        draw_environment();
        (void)svm_step(&vm);
        put_trace_line(step);
    }
    return 0;
}
