/*
 * swarmvm conformance harness, Cortex-M4F platform for QEMU mps2-an386 (bare metal).
 *
 * Output goes to the host through ARM semihosting (newlib's stdout with rdimon), fully
 * buffered so that a whole batch costs a few hundred semihosting calls; main's return value
 * becomes QEMU's exit status. With -DSVM_HARNESS_CYCLES the SysTick counter times each step.
 * QEMU does not model Cortex-M4 cycle timing: run it with `-icount shift=10` (every
 * instruction advances the virtual clock by 1,024 ns, SysTick counts the 25 MHz system clock,
 * i.e. 25.6 ticks per instruction) and the count reported is of instructions, not cycles.
 */
#include "svm_harness.h"

#include <stdio.h>

void svm_platform_write(const char *text, uint16_t length)
{
    (void)fwrite(text, 1, length, stdout);
}

#ifdef SVM_HARNESS_CYCLES
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_ENABLE_CPU_CLOCK 0x5u      /* ENABLE | CLKSOURCE = processor clock, no interrupt */
#define SYST_MASK 0x00FFFFFFu
#define NS_PER_INSTRUCTION 1024u        /* -icount shift=10 */
#define NS_PER_TICK 40u                 /* mps2 SYSCLK, 25 MHz */

static uint32_t started;
static uint32_t overhead;

void svm_platform_timer_start(void)
{
    started = SYST_CVR;
}

static uint32_t elapsed_instructions(void)
{
    uint32_t ticks = (started - SYST_CVR) & SYST_MASK;      /* SysTick counts down */
    return (ticks * NS_PER_TICK + NS_PER_INSTRUCTION / 2u) / NS_PER_INSTRUCTION;
}

uint32_t svm_platform_timer_stop(void)
{
    return elapsed_instructions() - overhead;
}

static void timer_init(void)
{
    SYST_RVR = SYST_MASK;
    SYST_CVR = 0u;
    SYST_CSR = SYST_ENABLE_CPU_CLOCK;
    svm_platform_timer_start();
    overhead = elapsed_instructions();
}
#endif

int svm_platform_start(void)
{
    static char buffer[4096];
    (void)setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
#ifdef SVM_HARNESS_CYCLES
    timer_init();
#endif
    return 0;
}

/* main's return value goes to exit() (startup.c), which flushes stdout. */
int svm_platform_stop(int status)
{
    return status;
}
