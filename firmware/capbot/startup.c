/* Reset path of the bare-metal Cortex-M4F build (QEMU mps2-an386): the vector table,
 * then copy .data from flash, zero .bss, enable the FPU, open the semihosting streams and
 * hand main's return value to exit() so that QEMU's semihosting makes it the exit status. */

#include <stdint.h>
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
    exit(main());
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
