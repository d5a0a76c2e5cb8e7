/* Reset path of the bare-metal Cortex-M4F build (QEMU mps2-an386): the vector table,
 * then copy .data from flash, zero .bss, enable the FPU, open the semihosting streams and
 * hand main's return value to exit() so that QEMU's semihosting makes it the exit status.
 *
 * Built with -DSVM_STACK_PAINT (make ... CAPBOT_CFLAGS=-DSVM_STACK_PAINT), it also measures
 * the deepest stack main reached, to cross-check the bound `swarmvm footprint` computes
 * (docs/footprint.md, "Stack"): the STACK_PAINT_BYTES below the stack pointer are filled with
 * PAINT before main is called, and when main returns the lowest word no longer holding it gives
 * main's depth, printed on stderr through semihosting ("stack: main used N B"). A word pushed
 * with the paint's value at the very bottom would read 4 B short; the bound is what is checked. */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start__[], __bss_end__[];
extern uint32_t __stack_top[];

extern void initialise_monitor_handles(void);
extern int main(void);

void Reset_Handler(void);
void Fault_Handler(void);

/* System Control Block: Coprocessor Access Control Register. */
#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)

#ifdef SVM_STACK_PAINT
#define STACK_PAINT_BYTES 16384u        /* far more than main's bound, far less than the heap's room */
#define PAINT 0xA5A5A5A5u

static void put_decimal(uint32_t value)
{
    char digits[10];
    unsigned n = 0;
    do {
        digits[n++] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value != 0u);
    while (n > 0u) {
        (void)fputc(digits[--n], stderr);
    }
}

/* main, called with the stack below this function's frame painted; its depth reported. Not
 * inlined, so that the painting loop runs in a frame main never reuses. */
__attribute__((noinline)) static int painted_main(void)
{
    uint32_t *top;
    volatile uint32_t *word;            /* volatile: a loop of stores, not a memset whose own frame is painted */
    int status;
    __asm__ volatile ("mov %0, sp" : "=r"(top));
    for (word = top - STACK_PAINT_BYTES / 4u; word < top; ++word) {
        *word = PAINT;
    }
    status = main();
    for (word = top - STACK_PAINT_BYTES / 4u; word < top && *word == PAINT; ++word) {
    }
    (void)fputs("stack: main used ", stderr);
    put_decimal((uint32_t)((uintptr_t)top - (uintptr_t)word));
    (void)fputs(" B\n", stderr);
    return status;
}
#endif

void Reset_Handler(void)
{
    uint32_t *src = __data_load;
    uint32_t *dst = __data_start;
    while (dst < __data_end) {
        *dst++ = *src++;
    }
    for (dst = __bss_start__; dst < __bss_end__; ++dst) {
        *dst = 0u;
    }
    /* The hard-float ABI uses the FPU registers from the first float operation on. */
    SCB_CPACR |= CPACR_CP10_CP11_FULL;
    __asm__ volatile ("dsb\n\tisb" ::: "memory");
    initialise_monitor_handles();
#ifdef SVM_STACK_PAINT
    exit(painted_main());
#else
    exit(main());
#endif
}

/* Newlib's exit() runs the destructor list, which calls _fini (normally from crti.o, left
 * out with -nostartfiles). This C program has no destructors. */
void _fini(void);
void _fini(void) {}

/* A fault ends the run with a distinctive status instead of hanging until the timeout. */
void Fault_Handler(void)
{
    _Exit(0x7f);
}

/* Initial stack pointer, reset, then NMI, HardFault, MemManage, BusFault, UsageFault.
 * Nothing enables interrupts, so the remaining vectors are not needed. */
typedef void (*vector_t)(void);
__attribute__((section(".vectors"), used))
static const vector_t vectors[] = {
    (vector_t)(uintptr_t)__stack_top,
    Reset_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
};
