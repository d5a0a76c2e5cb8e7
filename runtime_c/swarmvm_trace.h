/*
 * The canonical trace line of docs/conformance.md, "<step> <fired> <states> <violations>",
 * printed through a character output function: the one C implementation, used by the
 * conformance harness, the emulated robot applications and the demos, and by any robot
 * program that wants to log what its VM does. No stdio, no heap: it runs on the ATmega328P.
 * Header-only (static inline) so that a build including it needs no extra source file.
 */
#ifndef SWARMVM_TRACE_H
#define SWARMVM_TRACE_H

#include "swarmvm.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef void (*svm_putc_fn)(char c);

static inline void svm_put_text(svm_putc_fn put, const char *text)
{
    while (*text != '\0') {
        put(*text++);
    }
}

static inline void svm_put_decimal(svm_putc_fn put, uint32_t value)
{
    char digits[10];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value != 0u);
    while (n != 0u) {
        put(digits[--n]);
    }
}

/* "EV_<name>", or "EV_<index>" for an image without names. The name is read from the image a
 * byte at a time (names hold up to 255 characters: no buffer to size, none cut short). */
static inline void svm_put_event(svm_putc_fn put, const svm_vm_t *vm, uint8_t event)
{
    uint16_t at = vm->names_at;
    uint8_t e, left;
    svm_put_text(put, "EV_");
    if (!svm_has_names(vm)) {
        svm_put_decimal(put, event);
        return;
    }
    for (e = 0; e < event; e++) {
        at = (uint16_t)(at + 1u + svm_image_byte(vm, at));
    }
    for (left = svm_image_byte(vm, at); left != 0u; left--) {
        at++;
        put((char)svm_image_byte(vm, at));
    }
}

/* One trace line, without the newline: `fired` holds the `count` events of the step. */
static inline void svm_put_trace_line(svm_putc_fn put, const svm_vm_t *vm, uint32_t step,
                                      const uint8_t *fired, uint8_t count)
{
    uint8_t k;
    svm_put_decimal(put, step);
    put(' ');
    if (count == 0u) {
        put('-');
    }
    for (k = 0; k < count; k++) {
        if (k != 0u) {
            put(',');
        }
        svm_put_event(put, vm, fired[k]);
    }
    put(' ');
    for (k = 0; k < svm_num_supervisors(vm); k++) {
        if (k != 0u) {
            put(',');
        }
        svm_put_decimal(put, svm_state(vm, k));
    }
    put(' ');
    svm_put_decimal(put, svm_violations(vm));
}

#ifdef __cplusplus
}
#endif

#endif
