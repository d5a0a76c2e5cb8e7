/*
 * Emulator-only implementation of kilolib.h for simavr (ATmega328P, 8 MHz), written for the
 * swarmvm project. It is NOT kilolib: no motors, LEDs, IR or calibration. It runs setup() and
 * then loop() KILO_EMU_LOOPS times (default 100), advancing kilo_ticks once per loop, hands
 * the application's outgoing message back as sent, and writes what the robot would do on
 * USART0 (simavr prints it), one line per call: "color <c>", "motors <l> <r>", "tx <hex>".
 * It ends with cli(); sleep_cpu(), which simavr reports as the end of the run.
 */
#include "kilolib.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <util/crc16.h>

#ifndef KILO_EMU_LOOPS
#define KILO_EMU_LOOPS 100u
#endif

message_rx_t kilo_message_rx;
message_tx_t kilo_message_tx;
message_tx_success_t kilo_message_tx_success;
volatile uint32_t kilo_ticks;
uint16_t kilo_uid;
uint8_t kilo_turn_left = 70;
uint8_t kilo_turn_right = 70;
uint8_t kilo_straight_left = 70;
uint8_t kilo_straight_right = 70;

static uint16_t rand_state = 0xACE1u;

static void put(char c)
{
    loop_until_bit_is_set(UCSR0A, UDRE0);
    UDR0 = (uint8_t)c;
}

static void put_text(const char *s)
{
    while (*s != '\0') {
        put(*s++);
    }
}

static void put_uint(uint16_t value)
{
    char digits[5];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value != 0u);
    while (n != 0u) {
        put(digits[--n]);
    }
}

static void put_hex(uint8_t value)
{
    static const char hex[] = "0123456789abcdef";
    put(hex[value >> 4]);
    put(hex[value & 0x0Fu]);
}

void kilo_init(void)
{
    UBRR0H = 0;
    UBRR0L = 0;
    UCSR0A = (uint8_t)(1u << U2X0);
    UCSR0B = (uint8_t)(1u << TXEN0);
    UCSR0C = (uint8_t)((1u << UCSZ01) | (1u << UCSZ00));
    kilo_ticks = 0;
}

void kilo_start(void (*setup)(void), void (*loop)(void))
{
    uint16_t n;
    setup();
    for (n = 0; n < KILO_EMU_LOOPS; n++) {
        message_t *out;
        loop();
        out = kilo_message_tx != 0 ? kilo_message_tx() : 0;
        if (out != 0) {
            uint8_t i;
            put_text("tx ");
            for (i = 0; i < sizeof out->data; i++) {
                put_hex(out->data[i]);
            }
            put('\n');
            if (kilo_message_tx_success != 0) {
                kilo_message_tx_success();
            }
        }
        kilo_ticks++;
    }
    put_text("end\n");
    cli();
    sleep_enable();
    sleep_cpu();
}

void set_motors(uint8_t left, uint8_t right)
{
    put_text("motors ");
    put_uint(left);
    put(' ');
    put_uint(right);
    put('\n');
}

void spinup_motors(void)
{
    set_motors(255, 255);
}

void set_color(uint8_t color)
{
    put_text("color ");
    put_uint(color);
    put('\n');
}

int16_t get_ambientlight(void)
{
    return 512;
}

int16_t get_voltage(void)
{
    return 700;
}

uint8_t estimate_distance(const distance_measurement_t *distance)
{
    return (uint8_t)(distance->high_gain > 255 ? 255 : (distance->high_gain < 0 ? 0 : distance->high_gain));
}

uint8_t rand_soft(void)
{
    rand_state ^= (uint16_t)(rand_state << 7);
    rand_state ^= (uint16_t)(rand_state >> 9);
    rand_state ^= (uint16_t)(rand_state << 8);
    return (uint8_t)rand_state;
}

uint8_t rand_hard(void)
{
    return rand_soft();
}

uint16_t message_crc(const message_t *message)
{
    uint16_t crc = 0xFFFFu;
    uint8_t i;
    for (i = 0; i < sizeof message->data; i++) {
        crc = _crc_ccitt_update(crc, message->data[i]);
    }
    return _crc_ccitt_update(crc, (uint8_t)message->type);
}

void delay(uint16_t ms)
{
    (void)ms;
}
