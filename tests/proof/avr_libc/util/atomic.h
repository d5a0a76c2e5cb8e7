/* Proof stand-in of avr-libc's <util/atomic.h> (tests/proof/avr_libc/README.md), not avr-libc
 * code: the block's body runs once, as avr-libc's does with interrupts off; the interrupts
 * themselves are outside the analysis (docs/proof.md, "What is proved"). */
#ifndef PROOF_UTIL_ATOMIC_H
#define PROOF_UTIL_ATOMIC_H
#include <stdint.h>
#define ATOMIC_RESTORESTATE 0
#define ATOMIC_BLOCK(type) for (uint8_t proof_atomic_once = 1u; proof_atomic_once != 0u; proof_atomic_once = 0u)
#endif
