/*
 * STAND-IN, DECLARATIONS ONLY: the few Zephyr kernel names a generated CapBot main.c uses, so
 * that tests can compile it without the nRF Connect SDK (tests/targets/capbot/test_capbot_target.py). Not
 * Zephyr; the real build uses Zephyr's own <zephyr/kernel.h>.
 */
#ifndef ZEPHYR_STANDIN_KERNEL_H
#define ZEPHYR_STANDIN_KERNEL_H

#include <stddef.h>   /* NULL, as Zephyr's kernel.h provides it */
#include <stdint.h>

typedef struct {
    int64_t ticks;
} k_timeout_t;

struct k_timer;
typedef void (*k_timer_expiry_t)(struct k_timer *timer);
typedef void (*k_timer_stop_t)(struct k_timer *timer);

struct k_timer {
    k_timer_expiry_t expiry_fn;
    k_timer_stop_t stop_fn;
};

k_timeout_t z_timeout_ms(int32_t ms);
#define K_MSEC(ms) z_timeout_ms(ms)
#define K_TIMER_DEFINE(name, expiry, stop) struct k_timer name = {expiry, stop}

void k_timer_start(struct k_timer *timer, k_timeout_t duration, k_timeout_t period);
uint32_t k_timer_status_sync(struct k_timer *timer);
int32_t k_msleep(int32_t ms);

#endif
