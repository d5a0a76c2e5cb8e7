/*
 * The conformance batch of the flash-page harness (page_harness.c), read at run time instead
 * of compiled in: firmware/harness/svm_harness.c includes "svm_cases.h" for its batch, and
 * this one maps the names it uses onto the batch the harness found in memory, so that ONE
 * harness binary replays whichever supervisor the logic page holds. The image is the logic
 * page's (or the compiled-in fallback's); the scripts and runs come in a second blob (format
 * in page_harness.c). No RAM copy pass: its buffer would need a compile-time length.
 */
#ifndef SVM_CASES_H
#define SVM_CASES_H

#include <stdint.h>

struct page_batch {
    const uint8_t *image;
    const uint8_t *rows;        /* SVM_CASES_STEPS rows of SVM_CASES_MASK_BYTES per script */
    const uint8_t *runs;        /* per run: option flags, script index, seed (u32 LE) */
    uint16_t image_length;
    uint16_t steps;
    uint16_t num_runs;
    uint8_t mask_bytes;
};

extern struct page_batch page_batch;

#define SVM_CASES_IMAGE_LEN (page_batch.image_length)
#define SVM_CASES_MASK_BYTES (page_batch.mask_bytes)
#define SVM_CASES_STEPS (page_batch.steps)
#define SVM_CASES_RUNS (page_batch.num_runs)
#define SVM_CASES_RAM_COPY 0
#define SVM_CASES_RUNTIME_BINDINGS 0
#define svm_case_image (page_batch.image)
#define svm_case_rows (page_batch.rows)
#define svm_case_runs (page_batch.runs)

#endif
