/*
 * swarmvm conformance harness, ATmega328P platform (runs in simavr).
 *
 * Output goes to USART0 (simavr prints it on stderr, a line at a time); the run ends with
 * cli(); sleep_cpu(), which simavr reports as a normal exit. With -DSVM_HARNESS_CYCLES,
 * Timer1 at prescaler 1 counts the CPU cycles of each step (a step must stay under 65,536).
 * With -DSVM_HARNESS_EEPROM the image is also written to EEPROM and run from there, from the
 * first address kilolib leaves free (swarmvm_kilobot_eeprom.h): never over a Kilobot's
 * calibration.
 */
#include "svm_harness.h"
#include "swarmvm_kilobot_eeprom.h"

#include <avr/eeprom.h>
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>

void svm_platform_write(const char *text, uint16_t length)
{
    for (; length != 0u; length--) {
        loop_until_bit_is_set(UCSR0A, UDRE0);
        UDR0 = (uint8_t)*text++;
    }
}

#ifdef SVM_HARNESS_EEPROM
const uint8_t *svm_platform_to_eeprom(const uint8_t *image, uint16_t length)
{
    uint8_t *at = (uint8_t *)(uintptr_t)SVM_KILOBOT_EEPROM_FREE;
    uint16_t i;
    for (i = 0; i < length; i++) {
        eeprom_update_byte(at + i, pgm_read_byte(image + i));
    }
    return at;
}
#endif

#ifdef SVM_HARNESS_CYCLES
static uint16_t timer_overhead;

void svm_platform_timer_start(void)
{
    TCNT1 = 0;
}

uint32_t svm_platform_timer_stop(void)
{
    uint16_t now = TCNT1;
    return (uint32_t)(uint16_t)(now - timer_overhead);
}

static void timer_init(void)
{
    TCCR1A = 0;
    TCCR1B = (uint8_t)(1u << CS10);
    svm_platform_timer_start();
    timer_overhead = TCNT1;
}
#endif

int svm_platform_start(void)
{
    UBRR0H = 0;
    UBRR0L = 0;
    UCSR0A = (uint8_t)(1u << U2X0);
    UCSR0B = (uint8_t)(1u << TXEN0);
    UCSR0C = (uint8_t)((1u << UCSZ01) | (1u << UCSZ00));
#ifdef SVM_HARNESS_CYCLES
    timer_init();
#endif
    return 0;
}

/* The status is not reported: simavr ends the run at the sleep, and the output says the rest. */
int svm_platform_stop(int status)
{
    loop_until_bit_is_set(UCSR0A, TXC0);
    cli();
    sleep_enable();
    sleep_cpu();
    return status;
}
