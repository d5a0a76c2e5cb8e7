/*
 * STAND-IN for the FreeBot library's "freebot.h" (KU Leuven's FreeBot API v2: fb_io.h, fb_pwr.h,
 * fb_motor.h; the published program's CMakeLists.txt builds it from lib/freebot/, which the
 * published folder does not hold). The functions FreeBot's main.c calls, with the API's
 * signatures; the values of D15, D16 and V_* are this stand-in's. Behaviour (freebot_driver.c):
 * LEDs and motor commands are logged, fb_v_measure returns a fixed 2500 mV. Not the FreeBot API.
 */
#ifndef FREEBOT_STANDIN_FREEBOT_H
#define FREEBOT_STANDIN_FREEBOT_H

#include <stdint.h>

/* fb_io.h */
#define D15 15
#define D16 16
int fb_io_init(void);
void fb_set_led(uint8_t led_id);
void fb_clear_led(uint8_t led_id);
void fb_toggle_led(uint8_t led_id);
int fb_read_btn(void);

/* fb_pwr.h */
#define V_CAP 0
#define V_MOTOR 1
#define V_IN 2
int fb_pwr_init(void);
int fb_v_measure(void);
int fb_v_measure_select(int v_sel);

/* fb_motor.h */
int fb_motor_init(void);
void fb_stop(void);
void fb_straight_forw(void);
void fb_straight_back(void);
void fb_side_right(void);
void fb_side_left(void);
void fb_side_d45(void);
void fb_side_d135(void);
void fb_side_d225(void);
void fb_side_d315(void);
void fb_rotate_cw(void);
void fb_rotate_ccw(void);

/* freebot.h */
int fb_init(void);

#endif
