/*
 * swarmvm conformance harness: the platform interface.
 *
 * svm_harness.c (common to every platform) holds main(): it replays the event scripts of one
 * conformance batch (the generated header "svm_cases.h", see tests/conformance/c_harness.py) and
 * prints the canonical trace lines of docs/conformance.md. A platform file supplies the functions
 * below and calls nothing of the harness: the dependency runs one way, harness to platform.
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

/* Set up output (and the cycle timer) before the batch. Returns 0 to run the batch, or the exit
 * status to stop with when the platform has nothing to run (having said why on its output). */
int svm_platform_start(void);

/* Write `length` characters of output (part of a line, or up to its end). The harness collects
 * them a line (or a buffer) at a time: one call, not one per character. */
void svm_platform_write(const char *text, uint16_t length);

/* After the batch: flush the output and stop the machine. `status` is 0 when the image loaded
 * (nonzero otherwise, or the start's status); the return value becomes main's, on platforms
 * where main returns. */
int svm_platform_stop(int status);

#ifdef SVM_HARNESS_EEPROM
/* Copy a program-memory image into EEPROM; returns its EEPROM address. */
const uint8_t *svm_platform_to_eeprom(const uint8_t *image, uint16_t length);
#endif

#ifdef SVM_HARNESS_CYCLES
/* Start a cycle count / return the cycles since the start (calibrated, so that an empty
 * start-stop pair reads 0). */
void svm_platform_timer_start(void);
uint32_t svm_platform_timer_stop(void);
#endif

#endif /* SVM_HARNESS_H */
