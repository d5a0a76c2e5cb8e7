/*
 * Emulator-only implementation of kilolib.h for simavr (ATmega328P, 8 MHz), written for the
 * swarmvm project. It is NOT kilolib: no motors, LEDs, IR or calibration. It runs setup() and
 * then loop() KILO_EMU_LOOPS times (default 100), advancing kilo_ticks once per loop, hands
 * the application's outgoing message back as sent, and writes what the robot would do on
 * USART0 (simavr prints it), one line per call: "color <c>", "motors <l> <r>", "tx <hex>".
 * A build with -DKILO_EMU_SCRIPT also delivers scripted incoming messages (kilolib_emu.h).
 * It ends with cli(); sleep_cpu(), which simavr reports as the end of the run.
 */
#include "kilolib.h"
#include "kilolib_emu.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>
#include <util/crc16.h>

#ifdef KILO_EMU_SCRIPT
#include "kilo_emu_script.h"
#endif

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

void kilo_emu_put(char c)
{
    loop_until_bit_is_set(UCSR0A, UDRE0);
    UDR0 = (uint8_t)c;
}

void kilo_emu_print(const char *s)
{
    while (*s != '\0') {
        kilo_emu_put(*s++);
    }
}

void kilo_emu_print_uint(uint16_t value)
{
    char digits[5];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value != 0u);
    while (n != 0u) {
        kilo_emu_put(digits[--n]);
    }
}

static void put_hex(uint8_t value)
{
    static const char hex[] = "0123456789abcdef";
    kilo_emu_put(hex[value >> 4]);
    kilo_emu_put(hex[value & 0x0Fu]);
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

__attribute__((weak)) void kilo_emu_after_loop(void)
{
}

#ifdef KILO_EMU_SCRIPT
/* Hand the scripted messages of loop `n` to the application; returns the next entry. */
static uint16_t receive(uint16_t next, uint16_t n)
{
    while (next < KILO_EMU_SCRIPT_COUNT && pgm_read_word(&kilo_emu_script[next].loop) == n) {
        message_t in;
        distance_measurement_t distance = {0, 0};
        memcpy_P(in.data, kilo_emu_script[next].data, sizeof in.data);
        in.type = pgm_read_byte(&kilo_emu_script[next].type);
        in.crc = message_crc(&in);
        if (kilo_message_rx != 0) {
            kilo_message_rx(&in, &distance);
        }
        next++;
    }
    return next;
}
#endif

void kilo_start(void (*setup)(void), void (*loop)(void))
{
    uint16_t n;
#ifdef KILO_EMU_SCRIPT
    uint16_t next = 0;
#endif
    setup();
    for (n = 0; n < KILO_EMU_LOOPS; n++) {
        message_t *out;
#ifdef KILO_EMU_SCRIPT
        next = receive(next, n);
#endif
        loop();
        kilo_emu_after_loop();
        out = kilo_message_tx != 0 ? kilo_message_tx() : 0;
        if (out != 0) {
            uint8_t i;
            kilo_emu_print("tx ");
            for (i = 0; i < sizeof out->data; i++) {
                put_hex(out->data[i]);
            }
            kilo_emu_put('\n');
            if (kilo_message_tx_success != 0) {
                kilo_message_tx_success();
            }
        }
        kilo_ticks++;
    }
    kilo_emu_print("end\n");
    cli();
    sleep_enable();
    sleep_cpu();
}

void set_motors(uint8_t left, uint8_t right)
{
    kilo_emu_print("motors ");
    kilo_emu_print_uint(left);
    kilo_emu_put(' ');
    kilo_emu_print_uint(right);
    kilo_emu_put('\n');
}

void spinup_motors(void)
{
    set_motors(255, 255);
}

void set_color(uint8_t color)
{
    kilo_emu_print("color ");
    kilo_emu_print_uint(color);
    kilo_emu_put('\n');
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
