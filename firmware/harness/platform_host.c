/* swarmvm conformance harness, host platform: output on stdout. */
#include "svm_harness.h"

#include <stdio.h>

void svm_harness_putc(char c)
{
    putchar(c);
}

int main(void)
{
    return svm_harness_run();
}
