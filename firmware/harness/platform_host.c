/*
 * swarmvm conformance harness, host platform: output on stdout. A trace line is a few dozen
 * characters put one at a time, so they go through a buffer of the harness's own, written out
 * when full and at the end: stdio's per-character call (with its lock) would cost more than the
 * step it reports.
 */
#include "svm_harness.h"

#include <stdio.h>

static char buffer[1 << 16];
static size_t used;

static void flush_buffer(void)
{
    (void)fwrite(buffer, 1, used, stdout);
    used = 0;
}

void svm_harness_putc(char c)
{
    if (used == sizeof buffer) {
        flush_buffer();
    }
    buffer[used++] = c;
}

int main(void)
{
    int status = svm_harness_run();
    flush_buffer();
    return status;
}
