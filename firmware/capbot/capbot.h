/*
 * STAND-IN, DECLARATIONS ONLY: the part of the CapBot library's API (capbot.h of the robot's
 * Zephyr firmware, by KU Leuven) that generated CapBot applications use, so that they compile
 * bare-metal for tests in QEMU. It is not the CapBot library; on the robot the real capbot.h
 * (CAPBOT_LIB in the generated CMakeLists.txt) is used. Definitions for QEMU: capbot_qemu.c.
 */
#ifndef CAPBOT_H
#define CAPBOT_H

#include <stdint.h>

typedef enum {
    CB_D15,
    CB_D16,
} cb_led_t;

/** Motor speeds (rpm). */
typedef struct {
    int front_left;
    int front_right;
    int back_left;
    int back_right;
} cb_motor_speed_t;

int cb_led_init(void);
int cb_led_write(cb_led_t led, uint8_t val);
int cb_btn_init(void);
int cb_btn_get(void);
int cb_measure_init(void);
int16_t cb_measure_vcap(void);
int cb_motor_init(void);
void cb_set_motor_speed(cb_motor_speed_t *speeds);
void cb_get_motor_speed(cb_motor_speed_t *speeds);
void cb_stop(void);

#endif /* CAPBOT_H */
