/*
 * swarmvm conformance harness, host platform: output on stdout, through a buffer of its own
 * written out when full and at the end (the harness hands over a line at a time; a stdio call
 * per line, with its lock, would still cost more than the step it reports).
 */
#include "svm_harness.h"

#include <stdio.h>
#include <string.h>

static char buffer[1 << 16];
static size_t used;

static void flush_buffer(void)
{
    (void)fwrite(buffer, 1, used, stdout);
    used = 0;
}

int svm_platform_start(void)
{
    return 0;
}

void svm_platform_write(const char *text, uint16_t length)
{
    if (length > sizeof buffer - used) {
        flush_buffer();
    }
    memcpy(buffer + used, text, length);
    used += length;
}

int svm_platform_stop(int status)
{
    flush_buffer();
    return status;
}
