"""The two programs benchmarks/flash_vs_published.py builds from one supervisor, the published
VM's and swarmvm's minimal profile's, and the header of the event script both step over.

Each is the VM, its tables and a small main that loads the tables and steps, calling the same
trivial checks and actions, so that what differs between the two is the VM. Built without
BENCH_CYCLES (flash and RAM) the main steps for ever on inputs the compiler cannot see. Built
with it, it steps once over the script, each step timed, and prints one line

    c <total> <worst> <steps> <overflow> <fired> <digest>      (hexadecimal)

the cost of the steps (sum and worst), the steps run, whether a step overflowed the timer, and
the events fired over the script and their digest (benchmarks/published_form/same_steps.py),
folded after each step, outside its timing. Output and timer are the conformance harness's
platform, linked in, not copied (the ``svm_platform_*`` functions of firmware/harness/svm_harness.h),
so the steps are timed as benchmarks/avr_cycles.py and benchmarks/m4_cycles.py time theirs: on
the ATmega328P firmware/harness/platform_avr.c, Timer1 at prescaler 1 in simavr, i.e. cycles
(and here a step that overflows its 16 bits is flagged); on the Cortex-M4F
firmware/capbot/platform_qemu.c, SysTick under QEMU ``-icount``, i.e. instructions, not cycles;
both calibrated as those benchmarks' are (the timer's own start taken off, not the call that
stops it, a few cycles or instructions a step on both sides)."""

from typing import Iterable

# What both programs share: the inputs of the current step by the program's own event numbers
# (filled from the script; volatile, so the compiler cannot see through them), the draw the
# published side's generator gives, and the cycles harness.
APP = r"""
#include <stdint.h>
#include "bench_inputs.h"
volatile uint8_t app_sink;
volatile uint8_t app_row[BENCH_ROW_BYTES];
volatile uint8_t app_draw;
static uint8_t app_bit(uint8_t event) { return (uint8_t)((app_row[event >> 3] >> (event & 7u)) & 1u); }
#ifdef BENCH_CYCLES
/* The events the step fired, by the program's own numbers, folded into the digest after it. */
static uint8_t app_log[256];
static uint8_t app_fired;
#define APP_FIRED(e) (app_log[app_fired++] = (uint8_t)(e))
/* Output and the step timer: the conformance harness's platform, linked in (platform_avr.c,
 * platform_qemu.c). On the ATmega328P Timer1 counts 16 bits: a step that overflows it raises
 * TOV1, read here after the step and before the next, outside the timing. */
#include "svm_harness.h"
#ifdef __AVR__
#include <avr/io.h>
static uint8_t app_overflow;
#define APP_OVERFLOW app_overflow
#define APP_CLEAR_OVERFLOW() (TIFR1 = (uint8_t)(1u << TOV1))
#define APP_NOTE_OVERFLOW() (app_overflow |= (uint8_t)(TIFR1 & (1u << TOV1)))
#else
#define APP_OVERFLOW 0u
#define APP_CLEAR_OVERFLOW() ((void)0)
#define APP_NOTE_OVERFLOW() ((void)0)
#endif
static uint32_t app_digest = 2166136261u;       /* FNV-1a, as same_steps.py */
static void app_fold(uint8_t byte) { app_digest = (app_digest ^ byte) * 16777619u; }
static char app_line[2 + 6 * 9 + 1];
static uint8_t app_hex(uint8_t at, uint32_t v)
{
    uint8_t i;
    for (i = 0; i < 8u; i++, v <<= 4) {
        app_line[at++] = "0123456789abcdef"[(uint8_t)(v >> 28)];
    }
    app_line[at++] = ' ';
    return at;
}
static void app_run(void)
{
    uint32_t total = 0, worst = 0, fired = 0, t;
    uint16_t step;
    uint8_t i, at;
    if (svm_platform_start() != 0) {
        return;
    }
    for (step = 0; step < BENCH_STEPS; step++) {
        for (i = 0; i < BENCH_ROW_BYTES; i++) {
            app_row[i] = APP_ROM_BYTE(&app_rows[step][i]);
        }
        app_draw = APP_ROM_BYTE(&app_draws[step]);
        APP_CLEAR_OVERFLOW();
        svm_platform_timer_start();
        BENCH_STEP();
        t = svm_platform_timer_stop();
        APP_NOTE_OVERFLOW();
        total += t;
        if (t > worst) worst = t;
        for (i = 0; i < app_fired; i++) {
            app_fold(app_log[i] < sizeof app_name_of ? (uint8_t)(app_name_of[app_log[i]] + 1u) : 0xFFu);
        }
        app_fold(0);
        fired += app_fired;
        app_fired = 0;
    }
    app_line[0] = 'c'; app_line[1] = ' ';
    at = app_hex(app_hex(app_hex(app_hex(app_hex(app_hex(2u, total), worst), BENCH_STEPS), APP_OVERFLOW), fired),
                 app_digest);
    app_line[at - 1u] = '\n';
    svm_platform_write(app_line, at);
    (void)svm_platform_stop(0);    /* on the ATmega328P it sleeps, which ends simavr's run */
}
#else
#define APP_FIRED(e) (app_sink = (uint8_t)(e))
static void app_run(void) { for (;;) { BENCH_STEP(); } }
#endif
"""

PUBLISHED_MAIN = r"""
#include "model.h"
#define BENCH_STEP() SCT_run_step()
""" + APP + r"""
uint8_t app_random(void)
{   /* The application's generator (kilolib's rand_soft on a Kilobot): here it replays, step by
     * step, the position among the enabled events of the one swarmvm's generator chose. */
    return app_draw;
}
static unsigned char app_check(void *data) { return app_bit((uint8_t)(uintptr_t)data); }
static void app_act(void *data) { APP_FIRED((uintptr_t)data); }
int main(void)
{
    uint8_t e;
    SCT_init();
    for (e = 0; e < NUM_EVENTS; e++) {
        SCT_add_callback(e, app_act, app_check, (void *)(uintptr_t)e);
    }
    app_run();
    return 0;
}
"""

SWARMVM_MAIN = r"""
#include "swarmvm.h"
extern const uint8_t bench_image[];   /* bench_tables.c (swarmvm.h declares it in the profile) */
static svm_vm_t vm;
#define BENCH_STEP() (void)svm_step(&vm)
""" + APP + r"""
static uint8_t app_dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    if (op == SVM_OP_CHECK) {
        return app_bit(event);
    }
    APP_FIRED(event);
    return 0;
}
int main(void)
{
    svm_init(&vm);
    svm_set_dispatch(&vm, app_dispatch);
    svm_set_options(&vm, BENCH_OPTIONS, BENCH_SEED);
    if (svm_load_P(&vm, bench_image, BENCH_IMAGE_SIZE) != SVM_OK) {
        return 1;
    }
    app_run();
    return 0;
}
"""

EMPTY = "int main(void) { for (;;) { } }\n"

# Where the script's tables live: program memory on the ATmega328P (read with pgm_read_byte),
# plain constants (flash) on the Cortex-M4.
ROM = """#ifdef __AVR__
#include <avr/pgmspace.h>
#define APP_ROM PROGMEM
#define APP_ROM_BYTE(p) pgm_read_byte(p)
#else
#define APP_ROM
#define APP_ROM_BYTE(p) (*(p))
#endif
"""


def c_bytes(data: Iterable[int]) -> str:
    return ",".join(str(b) for b in data)


def inputs_header(names_of: list[int], rows: list[set[int]], draws: Iterable[int], cycles: bool) -> str:
    """bench_inputs.h: each of the program's events' canonical index (its number -> the name),
    and in a cycles build the script: each step's true checks as a mask by the program's own
    numbers, and the published side's draw of each step."""
    row_bytes = (len(names_of) + 7) // 8
    text = ["#include <stdint.h>", "#define BENCH_ROW_BYTES %d" % row_bytes, "#define BENCH_STEPS %d" % len(rows),
            "static const uint8_t app_name_of[] = {%s};" % c_bytes(names_of)]
    if cycles:
        masks = [sum(1 << i for i, name in enumerate(names_of) if name in row).to_bytes(row_bytes, "little")
                 for row in rows]
        text += [ROM, "static const uint8_t app_rows[%d][%d] APP_ROM = {%s};"
                 % (len(rows), row_bytes, ",".join("{%s}" % c_bytes(m) for m in masks)),
                 "static const uint8_t app_draws[%d] APP_ROM = {%s};" % (len(rows), c_bytes(draws))]
    return "\n".join(text) + "\n"
