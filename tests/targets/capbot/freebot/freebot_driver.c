/*
 * Test driver and STAND-IN DEFINITIONS for the headers in include/ (Zephyr kernel, GPIO,
 * Bluetooth, NUS, settings, logging, the FreeBot API): what FreeBot's published main.c calls,
 * built unchanged around it by tests/targets/capbot/test_freebot_main.py, on the host (gcc) and
 * bare-metal for QEMU mps2-an386. Not Zephyr, not the nRF Connect SDK, not the FreeBot library:
 * none of them exists here. Time is simulated; there is no scheduler (threads are never started).
 *
 * The robot's input. main.c's SCT checks (check_atWork, check_notAtWork, check_atCharger,
 * check_notAtCharger) read the global x_coord, which the program sets in handle_msg() when a
 * phone sends "e<x>,<y>,<angle>" over the Nordic UART Service. This driver plays the phone: it
 * calls connected() once (the program's BT_CONN_CB_DEFINE callbacks) and delivers the event
 * script's messages to the program's registered bt_nus_cb.received, i.e. through the program's
 * own parsing. Script (freebot_script.h, written by the test): one byte per step,
 *   bits 0-1  message delivered before the step (while main sleeps): 0 none, else x code
 *   bits 2-3  message delivered DURING the step, after the (1 + bits 4-5)-th LOG_* call the
 *             program makes in it: 0 none, else x code. This models the Bluetooth RX thread
 *             preempting the main thread in the middle of SCT_run_step's polling, so that
 *             checks polled in one step see different positions: atWork and notAtWork (or
 *             atCharger and notAtCharger) both true in one step, the contradictory inputs.
 *   bits 6-7  y code of both messages (main's steering: RIGHT/LEFT/straight)
 * x codes: 1 "0.5" (at the charger), 2 "1.25" (between), 3 "2.5" (at work); the program's
 * thresholds are x_charge 0.63 and x_work 1.94.
 *
 * Steps. Step 0 is main's setup up to its first k_sleep; step s >= 1 is the s-th pass of main's
 * for(;;) loop (fb_set_led, SCT_run_step, motion), ended by its k_sleep(K_MSEC(100)). Every
 * k_sleep/k_msleep ends the current step; after step FREEBOT_STEPS it flushes the log and calls
 * exit(0).
 *
 * The log (stdout), one line per program LOG_ call or printk (with the supervisors' states at that
 * moment), per FreeBot API call, per NUS send, and one per step end with the states. The
 * states: the published VM's global sup_current_state[] (build (a)), or swarmvm's SCT_state()
 * in exact mode, in the published file's numbering (build (b), -DFREEBOT_SWARMVM).
 *
 * With -DFREEBOT_TRACE_CALLBACKS and the link option -Wl,--wrap=SCT_add_callback, every
 * callback and check main.c registers is wrapped (main.c's own calls, unchanged, reach
 * __wrap_SCT_add_callback, which registers a tracing trampoline with the VM through
 * __real_SCT_add_callback): the log then shows each call the VM makes, in order, "sct: check E =
 * V" (after the check ran) and "sct: callback E" (with the states as the callback sees them), E
 * the event's number (EV_x, the file's in both builds). A NULL stays NULL.
 *
 * rand(): the VMs' draw uses the C library's rand(), never seeded by main.c (seed 1 in glibc
 * and in newlib). -DFREEBOT_NEWLIB_RAND defines rand()/srand() here with newlib's algorithm
 * (64-bit LCG, multiplier 6364136223846793005, increment 1, result bits 32-62, seed 1), so that
 * a host build draws what the bare-metal newlib build draws and the two logs can be compared.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <zephyr/kernel.h>
#include <zephyr/device.h>
#include <zephyr/drivers/gpio.h>
#include <zephyr/bluetooth/bluetooth.h>
#include <zephyr/bluetooth/conn.h>
#include <zephyr/usb/usb_device.h>
#include <zephyr/settings/settings.h>
#include <zephyr/logging/log.h>
#include <bluetooth/services/nus.h>
#include "freebot.h"

#include "freebot_script.h"     /* FREEBOT_STEPS, freebot_script[] (the test writes it) */

#ifndef FREEBOT_SUPERVISORS
#define FREEBOT_SUPERVISORS 4
#endif

#ifdef FREEBOT_SWARMVM
unsigned long SCT_state(unsigned char supervisor);   /* swarmvm_sct.h, exact mode */
#define FREEBOT_STATE(i) ((unsigned long)SCT_state((unsigned char)(i)))
#else
extern unsigned long int sup_current_state[];       /* the published lib/sct/src/sct_*.c */
#define FREEBOT_STATE(i) (sup_current_state[(i)])
#endif

#ifdef FREEBOT_NEWLIB_RAND
static unsigned long long rand_next = 1;
void srand(unsigned int seed)
{
    rand_next = seed;
}
int rand(void)
{
    rand_next = rand_next * 6364136223846793005ULL + 1;
    return (int)((rand_next >> 32) & 0x7fffffffULL);
}
#endif

/* ---- the log ---------------------------------------------------------------------------- */

static unsigned long step;          /* 0: setup; s >= 1: the s-th pass of main's loop */
static uint32_t uptime_ms;
static int buffered;

static void out(const char *text)
{
    if (!buffered) {
        buffered = 1;
        (void)setvbuf(stdout, NULL, _IOFBF, 4096);
    }
    (void)fputs(text, stdout);
}

static void outf(const char *format, ...)
{
    char line[256];
    va_list args;
    va_start(args, format);
    (void)vsnprintf(line, sizeof line, format, args);
    va_end(args);
    out(line);
}

static void out_states(void)
{
    int i;
    for (i = 0; i < FREEBOT_SUPERVISORS; ++i) {
        outf(i ? " %lu" : "%lu", FREEBOT_STATE(i));
    }
}

#ifdef FREEBOT_TRACE_CALLBACKS
struct freebot_slot {
    unsigned char event;
    void (*callback)(void *);
    unsigned char (*check)(void *);
    void *data;
};
static struct freebot_slot slots[256];

void __real_SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void __wrap_SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);

static void traced_callback(void *data)
{
    struct freebot_slot *slot = (struct freebot_slot *)data;
    outf("%05lu sct: callback %u [", step, (unsigned)slot->event);
    out_states();
    out("]\n");
    slot->callback(slot->data);
}

static unsigned char traced_check(void *data)
{
    struct freebot_slot *slot = (struct freebot_slot *)data;
    unsigned char value = slot->check(slot->data);
    outf("%05lu sct: check %u = %u\n", step, (unsigned)slot->event, (unsigned)value);
    return value;
}

void __wrap_SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data)
{
    struct freebot_slot *slot = &slots[event];
    slot->event = event;
    slot->callback = clbk;
    slot->check = ci;
    slot->data = data;
    __real_SCT_add_callback(event, clbk != NULL ? traced_callback : NULL, ci != NULL ? traced_check : NULL, slot);
}
#endif

/* ---- the phone --------------------------------------------------------------------------- */

struct bt_conn {
    bt_addr_le_t dst;
    int refs;
};
static struct bt_conn phone = {{1, {{0x33, 0x00, 0x00, 0xee, 0xff, 0xc0}}}, 0};
static struct bt_nus_cb *nus;
static int delivering;              /* a message is being handled: its logs do not count */
static unsigned step_logs;          /* program LOG_* calls in this step */
static unsigned inject_after;       /* 0: nothing to deliver during this step */
static unsigned char inject_code;
static unsigned char y_code;

static const char *const x_text[4] = {"", "0.5", "1.25", "2.5"};
static const char *const y_text[4] = {"0.25", "0.625", "0.875", "0.5"};

static void deliver(unsigned char x_code)
{
    char message[32];
    int length = snprintf(message, sizeof message, "e%s,%s,90.0", x_text[x_code], y_text[y_code]);
    outf("%05lu phone: %s\n", step, message);
    if (nus != NULL && nus->received != NULL) {
        delivering = 1;
        /* with its terminator: handle_msg() hands the bytes to strtok */
        nus->received(&phone, (const uint8_t *)message, (uint16_t)(length + 1));
        delivering = 0;
    }
}

void z_log(int level, const char *format, ...)
{
    static const char *const names[] = {"none", "err", "wrn", "inf"};
    char text[200];
    va_list args;
    va_start(args, format);
    (void)vsnprintf(text, sizeof text, format, args);
    va_end(args);
    outf("%05lu <%s> %s [", step, names[level & 3], text);
    out_states();
    out("]\n");
    if (!delivering && inject_after != 0 && ++step_logs == inject_after) {
        inject_after = 0;
        deliver(inject_code);
    }
}

void printk(const char *fmt, ...)
{
    char text[200];
    va_list args;
    va_start(args, fmt);
    (void)vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    outf("%05lu printk: %s", step, text);
}

/* ---- kernel: simulated time, one step per sleep ------------------------------------------ */

k_timeout_t z_timeout_ms(int32_t ms)
{
    k_timeout_t timeout;
    timeout.ticks = ms;
    return timeout;
}

int32_t k_sleep(k_timeout_t timeout)
{
    unsigned char entry;
    if (timeout.ticks > 0) {
        uptime_ms += (uint32_t)timeout.ticks;
    }
    outf("%05lu end ", step);
    out_states();
    out("\n");
    if (step == 0 && z_bt_conn_cb != NULL && z_bt_conn_cb->connected != NULL) {
        z_bt_conn_cb->connected(&phone, 0);     /* the phone connects while main waits */
    }
    if (step >= FREEBOT_STEPS) {
        (void)fflush(stdout);
        exit(0);
    }
    entry = freebot_script[step];
    ++step;
    y_code = (unsigned char)(entry >> 6 & 3u);
    if ((entry & 3u) != 0u) {
        deliver((unsigned char)(entry & 3u));
    }
    step_logs = 0;
    inject_code = (unsigned char)(entry >> 2 & 3u);
    inject_after = inject_code != 0u ? 1u + (entry >> 4 & 3u) : 0u;
    return 0;
}

int32_t k_msleep(int32_t ms)
{
    return k_sleep(K_MSEC(ms));
}

int64_t k_uptime_get(void)
{
    return uptime_ms;
}

uint32_t k_uptime_get_32(void)
{
    return uptime_ms;
}

int k_sem_init(struct k_sem *sem, unsigned int initial_count, unsigned int limit)
{
    sem->count = initial_count;
    sem->limit = limit;
    return 0;
}

int k_sem_take(struct k_sem *sem, k_timeout_t timeout)
{
    (void)timeout;
    if (sem->count == 0u) {
        return -11;         /* -EAGAIN: it would block, and nothing else runs */
    }
    --sem->count;
    return 0;
}

void k_sem_give(struct k_sem *sem)
{
    if (sem->count < sem->limit) {
        ++sem->count;
    }
}

void k_timer_init(struct k_timer *timer, k_timer_expiry_t expiry_fn, k_timer_stop_t stop_fn)
{
    timer->expiry_fn = expiry_fn;
    timer->stop_fn = stop_fn;
}

void k_timer_start(struct k_timer *timer, k_timeout_t duration, k_timeout_t period)
{
    (void)timer;
    (void)duration;
    (void)period;
}

/* ---- devices, GPIO, settings, USB --------------------------------------------------------- */

const struct device z_dt_gpio0 = {"gpio@50000000"};

bool device_is_ready(const struct device *dev)
{
    return dev != NULL;
}

int gpio_pin_configure_dt(const struct gpio_dt_spec *spec, gpio_flags_t extra_flags)
{
    (void)spec;
    (void)extra_flags;
    return 0;
}

int gpio_pin_interrupt_configure_dt(const struct gpio_dt_spec *spec, gpio_flags_t flags)
{
    (void)spec;
    (void)flags;
    return 0;
}

int gpio_pin_get_dt(const struct gpio_dt_spec *spec)
{
    (void)spec;
    return 0;               /* the button is never pressed */
}

int gpio_pin_set_dt(const struct gpio_dt_spec *spec, int value)
{
    (void)spec;
    (void)value;
    return 0;
}

int gpio_add_callback(const struct device *port, struct gpio_callback *callback)
{
    (void)port;
    (void)callback;
    return 0;
}

int settings_load(void)
{
    return 0;
}

int usb_enable(usb_dc_status_callback status_cb)
{
    (void)status_cb;
    return 0;
}

/* ---- Bluetooth ----------------------------------------------------------------------------- */

int bt_enable(bt_ready_cb_t cb)
{
    if (cb != NULL) {
        cb(0);
    }
    return 0;
}

int bt_le_adv_start(const struct bt_le_adv_param *param, const struct bt_data *ad, size_t ad_len,
                    const struct bt_data *sd, size_t sd_len)
{
    (void)param;
    (void)ad;
    (void)sd;
    outf("%05lu bt: advertising, %u AD and %u SD structures\n", step, (unsigned)ad_len, (unsigned)sd_len);
    return 0;
}

int bt_addr_le_to_str(const bt_addr_le_t *addr, char *str, size_t len)
{
    const uint8_t *v = addr->a.val;
    return snprintf(str, len, "%02X:%02X:%02X:%02X:%02X:%02X (%s)", v[5], v[4], v[3], v[2], v[1], v[0],
                    addr->type ? "random" : "public");
}

struct bt_conn *bt_conn_ref(struct bt_conn *conn)
{
    ++conn->refs;
    return conn;
}

void bt_conn_unref(struct bt_conn *conn)
{
    --conn->refs;
}

const bt_addr_le_t *bt_conn_get_dst(const struct bt_conn *conn)
{
    return &conn->dst;
}

int bt_conn_auth_cb_register(const struct bt_conn_auth_cb *cb)
{
    (void)cb;
    return 0;
}

int bt_conn_auth_info_cb_register(struct bt_conn_auth_info_cb *cb)
{
    (void)cb;
    return 0;
}

int bt_conn_auth_passkey_confirm(struct bt_conn *conn)
{
    (void)conn;
    return 0;
}

int bt_conn_auth_cancel(struct bt_conn *conn)
{
    (void)conn;
    return 0;
}

int bt_nus_init(struct bt_nus_cb *callbacks)
{
    nus = callbacks;
    return 0;
}

int bt_nus_send(struct bt_conn *conn, const uint8_t *data, uint16_t len)
{
    uint16_t i;
    outf("%05lu nus send%s:", step, conn == NULL ? " (all)" : "");
    for (i = 0; i < len; ++i) {
        outf(" %02x", data[i]);
    }
    out("\n");
    return 0;
}

/* ---- the FreeBot API: logged --------------------------------------------------------------- */

static void fb(const char *what)
{
    outf("%05lu fb: %s\n", step, what);
}

int fb_init(void)
{
    fb("init");
    return 0;
}

int fb_io_init(void)
{
    return 0;
}

void fb_set_led(uint8_t led_id)
{
    outf("%05lu fb: led %u on\n", step, (unsigned)led_id);
}

void fb_clear_led(uint8_t led_id)
{
    outf("%05lu fb: led %u off\n", step, (unsigned)led_id);
}

void fb_toggle_led(uint8_t led_id)
{
    outf("%05lu fb: led %u toggle\n", step, (unsigned)led_id);
}

int fb_read_btn(void)
{
    return 0;
}

int fb_pwr_init(void)
{
    return 0;
}

int fb_v_measure(void)
{
    return 2500;
}

int fb_v_measure_select(int v_sel)
{
    outf("%05lu fb: measure %d\n", step, v_sel);
    return 0;
}

int fb_motor_init(void)
{
    fb("motor init");
    return 0;
}

void fb_stop(void) { fb("stop"); }
void fb_straight_forw(void) { fb("straight_forw"); }
void fb_straight_back(void) { fb("straight_back"); }
void fb_side_right(void) { fb("side_right"); }
void fb_side_left(void) { fb("side_left"); }
void fb_side_d45(void) { fb("side_d45"); }
void fb_side_d135(void) { fb("side_d135"); }
void fb_side_d225(void) { fb("side_d225"); }
void fb_side_d315(void) { fb("side_d315"); }
void fb_rotate_cw(void) { fb("rotate_cw"); }
void fb_rotate_ccw(void) { fb("rotate_ccw"); }
