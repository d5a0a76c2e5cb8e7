/*
 * swarmvm conformance harness: the platform interface.
 *
 * svm_harness.c (common to every platform) replays the event scripts of one conformance batch
 * (the generated header "svm_cases.h", see tests/conformance/c_harness.py) and prints the
 * canonical trace lines of docs/conformance.md. A platform supplies main(), which calls
 * svm_harness_run() and then stops the machine, and the functions below.
 *
 * Output, one line each:
 *   @<pass> <run>        before the trace of run <run>; pass 0 = image compiled in (flash),
 *                        pass 1 = the same image copied to RAM and loaded at run time,
 *                        pass 2 = copied to EEPROM and loaded from there (-DSVM_HARNESS_EEPROM)
 *   <trace line>         docs/conformance.md; with -DSVM_HARNESS_CYCLES followed by " ~<n>",
 *                        the cycles svm_step took (platforms with a cycle timer)
 *   @refused <code>      a corrupted copy of the image was refused with this svm_load code
 *   @error <code>        the image itself was refused: nothing else runs
 *   @end                 last line
 */
#ifndef SVM_HARNESS_H
#define SVM_HARNESS_H

#include <stdint.h>

/* Runs every run of the batch, both passes; returns 0 when the image loaded. */
int svm_harness_run(void);

/* Platform: write `length` characters of output (part of a line, or up to its end). The harness
 * collects them a line (or a buffer) at a time: one call, not one per character. */
void svm_harness_write(const char *text, uint16_t length);

#ifdef SVM_HARNESS_EEPROM
/* Platform: copy a program-memory image into EEPROM; returns its EEPROM address. */
const uint8_t *svm_harness_to_eeprom(const uint8_t *image, uint16_t length);
#endif

#ifdef SVM_HARNESS_CYCLES
/* Platform: start a cycle count / return the cycles since the start (calibrated, so that an
 * empty start-stop pair reads 0). */
void svm_harness_timer_start(void);
uint32_t svm_harness_timer_stop(void);
#endif

#endif /* SVM_HARNESS_H */
