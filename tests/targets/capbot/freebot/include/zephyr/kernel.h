/*
 * STAND-IN for Zephyr's <zephyr/kernel.h>: the kernel names FreeBot's published main.c uses, with
 * Zephyr's signatures (k_sleep(k_timeout_t), K_MSEC, K_FOREVER, k_msleep, k_uptime_get_32,
 * K_SEM_DEFINE and k_sem_*, K_THREAD_DEFINE, struct k_timer, printk), for the test that builds
 * that main.c unchanged (tests/targets/capbot/test_freebot_main.py). Not Zephyr, and no
 * scheduler: time is simulated and advances only in k_sleep/k_msleep, each call of which ends one
 * step of the test's event script (freebot_driver.c); after the script's last step k_sleep ends
 * the program with exit(0). Threads made with K_THREAD_DEFINE are recorded, NEVER STARTED (main's
 * SCT loop does not depend on them: FreeBot's only one, ble_write_thread, sends voltages).
 * k_timeout_t and K_MSEC are those of firmware/capbot/zephyr/kernel.h (the CapBot target's
 * stand-in), which this one extends; that one lacks the names above, so it is not included.
 */
#ifndef FREEBOT_STANDIN_ZEPHYR_KERNEL_H
#define FREEBOT_STANDIN_ZEPHYR_KERNEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <zephyr/sys/util.h>

typedef struct {
    int64_t ticks;          /* here: milliseconds */
} k_timeout_t;

k_timeout_t z_timeout_ms(int32_t ms);
#define K_MSEC(ms) z_timeout_ms(ms)
#define K_SECONDS(s) K_MSEC((s) * 1000)
#define K_NO_WAIT z_timeout_ms(0)
#define K_FOREVER z_timeout_ms(-1)

int32_t k_sleep(k_timeout_t timeout);
int32_t k_msleep(int32_t ms);
int64_t k_uptime_get(void);
uint32_t k_uptime_get_32(void);

struct k_sem {
    unsigned int count;
    unsigned int limit;
};
#define K_SEM_DEFINE(name, initial_count, count_limit) \
    struct k_sem name = {(initial_count), (count_limit)}
int k_sem_init(struct k_sem *sem, unsigned int initial_count, unsigned int limit);
int k_sem_take(struct k_sem *sem, k_timeout_t timeout);
void k_sem_give(struct k_sem *sem);

struct k_timer;
typedef void (*k_timer_expiry_t)(struct k_timer *timer);
typedef void (*k_timer_stop_t)(struct k_timer *timer);
struct k_timer {
    k_timer_expiry_t expiry_fn;
    k_timer_stop_t stop_fn;
};
void k_timer_init(struct k_timer *timer, k_timer_expiry_t expiry_fn, k_timer_stop_t stop_fn);
void k_timer_start(struct k_timer *timer, k_timeout_t duration, k_timeout_t period);

typedef void (*k_thread_entry_t)(void *p1, void *p2, void *p3);
struct k_thread {
    k_thread_entry_t entry;     /* recorded, never run: see the top of this file */
    size_t stack_size;
    int priority;
};
typedef struct k_thread *k_tid_t;
/* Zephyr's signature; the entry is cast as Zephyr's own macro does. */
#define K_THREAD_DEFINE(name, stack_size, entry, p1, p2, p3, prio, options, delay) \
    struct k_thread z_thread_obj_##name = {(k_thread_entry_t)(void (*)(void))(entry), (stack_size), (prio)}; \
    const k_tid_t name = &z_thread_obj_##name

void printk(const char *fmt, ...);

#endif
