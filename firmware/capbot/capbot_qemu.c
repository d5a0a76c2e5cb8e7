/*
 * The CapBot API of capbot.h (stand-in) on QEMU's mps2-an386, which has no robot: the motors
 * and LEDs keep the last value written, the button is never pressed and the supercapacitor
 * reads a constant voltage. Enough for the generated controller to link and run unchanged.
 */
#include "capbot.h"

#define VCAP_MV 4000

static cb_motor_speed_t motors;
static uint8_t leds;

int cb_led_init(void)
{
    leds = 0;
    return 0;
}

int cb_led_write(cb_led_t led, uint8_t val)
{
    uint8_t bit = (uint8_t)(1u << (unsigned)led);
    leds = val ? (uint8_t)(leds | bit) : (uint8_t)(leds & ~bit);
    return 0;
}

int cb_btn_init(void)
{
    return 0;
}

int cb_btn_get(void)
{
    return 0;
}

int cb_measure_init(void)
{
    return 0;
}

int16_t cb_measure_vcap(void)
{
    return VCAP_MV;
}

int cb_motor_init(void)
{
    cb_stop();
    return 0;
}

void cb_set_motor_speed(cb_motor_speed_t *speeds)
{
    motors = *speeds;
}

void cb_get_motor_speed(cb_motor_speed_t *speeds)
{
    *speeds = motors;
}

void cb_stop(void)
{
    static const cb_motor_speed_t stopped = {0, 0, 0, 0};
    motors = stopped;
}
