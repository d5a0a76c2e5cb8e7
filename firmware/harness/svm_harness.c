/*
 * swarmvm conformance harness, common part and main() (platform interface in svm_harness.h).
 *
 * One build per supervisor runs every run of its batch: options and seeds are run-time flags
 * of the VM. The event scripts are rows of event masks in program memory; the checks return
 * the current row's bits. Pass 0 binds callbacks at compile time (a dispatch function, no
 * RAM); pass 1 copies the image to RAM, binds callbacks at run time (svm_bind; left out with
 * SVM_CASES_RUNTIME_BINDINGS 0 when RAM is short) and swaps the copy in with svm_load, so
 * both the flash and the loaded path are compared with the reference.
 */
#include "svm_harness.h"
#include "swarmvm.h"
#include "swarmvm_trace.h"
#include "svm_cases.h"

#include <stddef.h>

static svm_vm_t vm;
static uint8_t row[SVM_MASK_BYTES];
static uint8_t fired[SVM_MAX_EVENTS];   /* a step fires each event at most once */
static uint8_t num_fired;

/* Bit e%8 of a mask byte, by table: AVR shifts by a variable count one bit per cycle pair, and
 * the cycle benchmark should measure the VM, not the harness's checks. */
static const uint8_t bit_of[8] = {0x01u, 0x02u, 0x04u, 0x08u, 0x10u, 0x20u, 0x40u, 0x80u};

static uint8_t row_has(uint8_t event)
{
    return (uint8_t)((row[event >> 3] & bit_of[event & 7u]) != 0u);
}

static void record(uint8_t event)
{
    if (num_fired < SVM_MAX_EVENTS) {
        fired[num_fired++] = event;
    }
}

/* Pass 0: compile-time dispatch. */
static uint8_t dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    if (op == SVM_OP_CHECK) {
        return row_has(event);
    }
    record(event);
    return 0;
}

#if SVM_CASES_RAM_COPY
static uint8_t ram_image[SVM_CASES_IMAGE_LEN];
#endif

#if SVM_CASES_RAM_COPY && SVM_CASES_RUNTIME_BINDINGS
/* Pass 1: runtime bindings; the event index travels in the data pointer. */
static svm_binding_t bindings[SVM_MAX_EVENTS];

static unsigned char bound_check(void *data)
{
    return row_has((uint8_t)(uintptr_t)data);
}

static void bound_action(void *data)
{
    record((uint8_t)(uintptr_t)data);
}
#endif

/* Output is collected here and handed to the platform when full or at a line's end (small on
 * AVR, whose RAM decides how complete the loaded pass is). */
#if defined(__AVR__)
#define OUT_BYTES 16u
#else
#define OUT_BYTES 128u
#endif
static char out[OUT_BYTES];
static uint16_t out_used;

static void flush_out(void)
{
    svm_platform_write(out, out_used);
    out_used = 0;
}

static void put_char(char c)
{
    if (out_used == OUT_BYTES) {
        flush_out();
    }
    out[out_used++] = c;
}

static void end_line(void)
{
    put_char('\n');
    flush_out();
}

static void put_str(const char *s)
{
    svm_put_text(put_char, s);
}

static void put_uint(uint32_t value)
{
    svm_put_decimal(put_char, value);
}

/* "@error <code>" (or another tag) and the end of the line: the harness's report of a load. */
static void put_result(const char *tag, int result)
{
    put_str(tag);
    put_uint((uint32_t)result);
    end_line();
}

static void put_trace_line(uint32_t step)
{
    svm_put_trace_line(put_char, &vm, step, fired, num_fired);
}

static uint32_t flash_u32(const uint8_t *p)
{
    return (uint32_t)SVM_FLASH_BYTE(p) | ((uint32_t)SVM_FLASH_BYTE(p + 1) << 8) |
           ((uint32_t)SVM_FLASH_BYTE(p + 2) << 16) | ((uint32_t)SVM_FLASH_BYTE(p + 3) << 24);
}

static void run_all(uint8_t pass)
{
    uint16_t run;
    uint32_t step;
    uint8_t i;
    for (run = 0; run < SVM_CASES_RUNS; run++) {
        const uint8_t *spec = svm_case_runs + 6u * run;
        const uint8_t *rows = svm_case_rows +
                              (uint32_t)SVM_FLASH_BYTE(spec + 1) * SVM_CASES_STEPS * SVM_CASES_MASK_BYTES;
        svm_set_options(&vm, SVM_FLASH_BYTE(spec), flash_u32(spec + 2));
        svm_reset(&vm);
        put_char('@');
        put_uint(pass);
        put_char(' ');
        put_uint(run);
        end_line();
        for (step = 0; step < SVM_CASES_STEPS; step++) {
            for (i = 0; i < SVM_CASES_MASK_BYTES; i++) {
                row[i] = SVM_FLASH_BYTE(rows + step * SVM_CASES_MASK_BYTES + i);
            }
            num_fired = 0;
#ifdef SVM_HARNESS_CYCLES
            {
                uint32_t cycles;
                svm_platform_timer_start();
                (void)svm_step(&vm);
                cycles = svm_platform_timer_stop();
                put_trace_line(step + 1u);
                put_str(" ~");
                put_uint(cycles);
            }
#else
            (void)svm_step(&vm);
            put_trace_line(step + 1u);
#endif
            end_line();
        }
    }
}

#if SVM_CASES_RAM_COPY
static void run_loaded(void)
{
    uint16_t i;
    int result;
#if SVM_CASES_RUNTIME_BINDINGS
    uint8_t e;
    svm_set_bindings(&vm, bindings, SVM_MAX_EVENTS);
    for (e = 0; e < svm_num_events(&vm); e++) {
        svm_check_fn check = svm_is_controllable(&vm, e) ? (svm_check_fn)0 : bound_check;
        (void)svm_bind(&vm, e, bound_action, check, (void *)(uintptr_t)e);
    }
    svm_set_dispatch(&vm, (svm_dispatch_fn)0);
#endif
    for (i = 0; i < SVM_CASES_IMAGE_LEN; i++) {
        ram_image[i] = SVM_FLASH_BYTE(svm_case_image + i);
    }
    /* A corrupted copy must be refused and leave the running logic in place. */
    ram_image[SVM_CASES_IMAGE_LEN / 2u] ^= 0x01u;
    result = svm_load(&vm, ram_image, SVM_CASES_IMAGE_LEN);
    ram_image[SVM_CASES_IMAGE_LEN / 2u] ^= 0x01u;
    put_result("@refused ", result);
    result = svm_load(&vm, ram_image, SVM_CASES_IMAGE_LEN);
    if (result != SVM_OK) {
        put_result("@error ", result);
        return;
    }
    run_all(1);
}
#endif

#ifdef SVM_HARNESS_EEPROM
/* Pass 2: the image copied to EEPROM by the platform and loaded from there. */
static void run_from_eeprom(void)
{
    const uint8_t *image = svm_platform_to_eeprom(svm_case_image, SVM_CASES_IMAGE_LEN);
    int result = svm_load_E(&vm, image, SVM_CASES_IMAGE_LEN);
    if (result != SVM_OK) {
        put_result("@error ", result);
        return;
    }
    run_all(2);
}
#endif

/* Every run of the batch, every pass; 0 when the image loaded. */
static int run_batch(void)
{
    int result;
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    result = svm_load_P(&vm, svm_case_image, SVM_CASES_IMAGE_LEN);
    if (result != SVM_OK) {
        put_result("@error ", result);
        put_str("@end");
        end_line();
        return 1;
    }
    run_all(0);
#if SVM_CASES_RAM_COPY
    run_loaded();
#endif
#ifdef SVM_HARNESS_EEPROM
    run_from_eeprom();
#endif
    put_str("@end");
    end_line();
    return 0;
}

int main(void)
{
    int status = svm_platform_start();
    if (status == 0) {
        status = run_batch();
    }
    return svm_platform_stop(status);
}
