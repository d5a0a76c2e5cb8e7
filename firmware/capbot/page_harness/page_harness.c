/*
 * Conformance harness of the CapBot flash-page build, QEMU mps2-an386: one binary for every
 * supervisor. At boot it validates the control-logic page (swarmvm_logic_page.h) and replays the
 * conformance batch against the page's image; when the page is refused it prints the code
 * and replays against the compiled-in fallback (-DSVM_APP=<model>: <model>_image of the
 * generated tables), as the application would run it. The batch's scripts and runs come in a
 * second blob that QEMU's loader writes at CASES_BLOB:
 *
 *   offset 0  "SVMC"           8  u8 event-mask bytes per row
 *          4  u16 steps        9  3 bytes zero
 *          6  u16 runs        12  u32 R, bytes of rows
 *         16  R bytes of rows (script after script), then runs x 6 bytes (svm_cases.h)
 *
 * Output: "@page <code>" (svm_validate of the page, 0 = runs it), then firmware/harness/'s
 * lines (svm_harness.h); "@cases" and exit status 3 when the blob is missing or too wide.
 * This file is the harness's platform (svm_harness.h); main() is the harness's.
 */
#include "swarmvm_logic_page.h"
#include "svm_cases.h"
#include "svm_harness.h"
#include SVM_APP_HEADER

#include <stdio.h>

#define CASES_BLOB ((const uint8_t *)0x00200000u)   /* SSRAM1, above the program and the page */
#define CASES_HEADER 16u

#define CAT_(a, b) a##b
#define CAT(a, b) CAT_(a, b)
#define FALLBACK_IMAGE CAT(SVM_APP, _image)

struct page_batch page_batch;

void svm_platform_write(const char *text, uint16_t length)
{
    (void)fwrite(text, 1, length, stdout);
}

static uint16_t u16_at(const uint8_t *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

/* Fills the script part of page_batch from the blob; 0 when there is no usable blob. */
static int read_cases(void)
{
    const uint8_t *blob = CASES_BLOB;
    uint32_t row_bytes = (uint32_t)u16_at(blob + 12) | ((uint32_t)u16_at(blob + 14) << 16);
    if (blob[0] != 'S' || blob[1] != 'V' || blob[2] != 'M' || blob[3] != 'C' ||
        blob[8] == 0u || blob[8] > SVM_MASK_BYTES) {
        return 0;
    }
    page_batch.steps = u16_at(blob + 4);
    page_batch.num_runs = u16_at(blob + 6);
    page_batch.mask_bytes = blob[8];
    page_batch.rows = blob + CASES_HEADER;
    page_batch.runs = blob + CASES_HEADER + row_bytes;
    return 1;
}

/* The batch's image (the page's or the fallback) and scripts; 3 when there are no scripts. */
int svm_platform_start(void)
{
    static char buffer[4096];
    int page = svm_logic_page_validate();
    (void)setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
    printf("@page %d\n", page);
    if (page == SVM_OK) {
        page_batch.image = svm_logic_page();
        page_batch.image_length = svm_logic_page_length();
    } else {
        page_batch.image = FALLBACK_IMAGE;
        page_batch.image_length = (uint16_t)sizeof FALLBACK_IMAGE;
    }
    if (!read_cases()) {
        printf("@cases\n");
        return 3;
    }
    return 0;
}

/* main's return value goes to exit() (startup.c), which flushes stdout. */
int svm_platform_stop(int status)
{
    return status;
}
