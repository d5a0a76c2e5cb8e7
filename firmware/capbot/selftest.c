/* Start-up self-test for the bare-metal Cortex-M4F build: prints through semihosting and
 * returns a status that proves .data was copied, .bss zeroed and the FPU enabled. */

#include <stdio.h>

static volatile unsigned initialised = 0x5eedu;
static volatile unsigned zeroed;
static volatile float half = 0.5f;

int main(void)
{
    float product = half * 3.0f;     /* faults unless CPACR gave access to the FPU */
    int ok = initialised == 0x5eedu && zeroed == 0u && product == 1.5f;
    printf("capbot selftest: data %s, bss %s, fpu %s\n",
           initialised == 0x5eedu ? "ok" : "BAD", zeroed == 0u ? "ok" : "BAD",
           product == 1.5f ? "ok" : "BAD");
    return ok ? 42 : 1;
}
