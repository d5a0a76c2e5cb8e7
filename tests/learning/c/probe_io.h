/*
 * Output for the learning probes: stdout on a host, USART0 on the ATmega328P (simavr shows it
 * on stderr). Test code only. A probe ends with probe_end(), which stops an AVR cleanly
 * (cli; sleep) so simavr exits.
 */
#ifndef PROBE_IO_H
#define PROBE_IO_H

#include <stdint.h>

#if defined(__AVR__)
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>
#include <string.h>
#define PROBE_CONST PROGMEM
static inline void probe_start(void)
{
    UBRR0 = 3;                               /* any rate: simavr does not time the line */
    UCSR0B = (uint8_t)(1 << TXEN0);
    UCSR0C = (uint8_t)((1 << UCSZ01) | (1 << UCSZ00));
}
static inline void probe_putc(char c)
{
    while (!(UCSR0A & (1 << UDRE0))) {
    }
    UDR0 = (uint8_t)c;
}
static inline void probe_end(void)
{
    cli();
    sleep_cpu();
}
#define PROBE_READ(dst, src, size) memcpy_P((dst), (src), (size))
#else
#include <stdio.h>
#include <string.h>
#define PROBE_CONST
static inline void probe_start(void)
{
}
static inline void probe_putc(char c)
{
    putchar(c);
}
static inline void probe_end(void)
{
    fflush(stdout);
}
#define PROBE_READ(dst, src, size) memcpy((dst), (src), (size))
#endif

static inline void probe_puts(const char *s)
{
    while (*s) {
        probe_putc(*s++);
    }
}

/* `size` bytes of `p` as hex, most significant byte first (little-endian machines). */
static inline void probe_hex(const void *p, uint8_t size)
{
    static const char digits[] = "0123456789abcdef";
    const uint8_t *b = (const uint8_t *)p;
    while (size--) {
        probe_putc(digits[b[size] >> 4]);
        probe_putc(digits[b[size] & 15]);
    }
}

static inline void probe_u32(uint32_t v)
{
    probe_hex(&v, 4);
}

#endif /* PROBE_IO_H */
