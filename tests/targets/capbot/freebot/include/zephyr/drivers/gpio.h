/*
 * STAND-IN for Zephyr's <zephyr/drivers/gpio.h>: the GPIO names FreeBot's main.c uses, with
 * Zephyr's types and signatures. Behaviour (freebot_driver.c): configuring succeeds and the
 * button never fires (the SCT loop does not read it). Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_ZEPHYR_DRIVERS_GPIO_H
#define FREEBOT_STANDIN_ZEPHYR_DRIVERS_GPIO_H

#include <stdint.h>
#include <zephyr/device.h>
#include <zephyr/devicetree.h>
#include <zephyr/sys/util.h>

typedef uint8_t gpio_pin_t;
typedef uint16_t gpio_dt_flags_t;
typedef uint32_t gpio_flags_t;
typedef uint32_t gpio_port_pins_t;

#define GPIO_INPUT (1U << 16)
#define GPIO_OUTPUT (1U << 17)
#define GPIO_INT_EDGE_TO_ACTIVE ((1U << 21) | (1U << 22) | (1U << 26) | (1U << 25))

struct gpio_dt_spec {
    const struct device *port;
    gpio_pin_t pin;
    gpio_dt_flags_t dt_flags;
};

extern const struct device z_dt_gpio0;
#define Z_GPIO_DT_SPEC(node_id, prop) \
    {.port = &node_id##_P_##prop##_CTLR, .pin = node_id##_P_##prop##_PIN, .dt_flags = node_id##_P_##prop##_FLAGS}
#define GPIO_DT_SPEC_GET(node_id, prop) Z_GPIO_DT_SPEC(node_id, prop)

struct gpio_callback;
typedef void (*gpio_callback_handler_t)(const struct device *port, struct gpio_callback *cb, gpio_port_pins_t pins);
struct gpio_callback {
    struct gpio_callback *next;     /* Zephyr: sys_snode_t node */
    gpio_callback_handler_t handler;
    gpio_port_pins_t pin_mask;
};

int gpio_pin_configure_dt(const struct gpio_dt_spec *spec, gpio_flags_t extra_flags);
int gpio_pin_interrupt_configure_dt(const struct gpio_dt_spec *spec, gpio_flags_t flags);
int gpio_pin_get_dt(const struct gpio_dt_spec *spec);
int gpio_pin_set_dt(const struct gpio_dt_spec *spec, int value);
int gpio_add_callback(const struct device *port, struct gpio_callback *callback);
static inline void gpio_init_callback(struct gpio_callback *callback, gpio_callback_handler_t handler,
                                      gpio_port_pins_t pin_mask)
{
    callback->handler = handler;
    callback->pin_mask = pin_mask;
}

#endif
