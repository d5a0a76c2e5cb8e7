/* Declaration-only stand-in for kilolib, written for the swarmvm project (kilolib itself is not
 * packaged anywhere reachable). It declares the part of kilolib's public API that generated
 * Kilobot applications use, with kilolib's names and shapes, so they compile here and against
 * the real library unchanged. firmware/kilobot/kilolib_emu.c implements it for simavr only.
 */
#ifndef KILOLIB_H
#define KILOLIB_H

#include <stdint.h>

/* A message: 9 bytes of payload, a type and a CRC (message_crc). Types from SPECIAL (0x80)
 * up are kilolib's own (boot loader, calibration) and never reach kilo_message_rx; an
 * application may use the others. */
typedef enum {
    NORMAL = 0,
    GPS = 1,
    SPECIAL = 0x80
} message_type_t;

typedef struct {
    uint8_t data[9];
    uint8_t type;
    uint16_t crc;
} message_t;

typedef struct {
    int16_t low_gain;
    int16_t high_gain;
} distance_measurement_t;

typedef void (*message_rx_t)(message_t *message, distance_measurement_t *distance);
typedef message_t *(*message_tx_t)(void);
typedef void (*message_tx_success_t)(void);

/* Callbacks the application sets before kilo_start. */
extern message_rx_t kilo_message_rx;
extern message_tx_t kilo_message_tx;
extern message_tx_success_t kilo_message_tx_success;

/* Clock ticks since start (about 31 per second), the robot's id, motor calibration. */
extern volatile uint32_t kilo_ticks;
extern uint16_t kilo_uid;
extern uint8_t kilo_turn_left;
extern uint8_t kilo_turn_right;
extern uint8_t kilo_straight_left;
extern uint8_t kilo_straight_right;

/* LED colour from 2-bit components. */
#define RGB(r, g, b) ((uint8_t)(((r) & 3) | (((g) & 3) << 2) | (((b) & 3) << 4)))

void kilo_init(void);
void kilo_start(void (*setup)(void), void (*loop)(void));

void set_motors(uint8_t left, uint8_t right);
void spinup_motors(void);
void set_color(uint8_t color);
int16_t get_ambientlight(void);
int16_t get_voltage(void);
uint8_t estimate_distance(const distance_measurement_t *distance);
uint8_t rand_soft(void);
uint8_t rand_hard(void);
uint16_t message_crc(const message_t *message);
void delay(uint16_t ms);

#endif /* KILOLIB_H */
