/* Proof stand-in of avr-libc's <avr/pgmspace.h> (tests/proof/avr_libc/README.md), not avr-libc
 * code: program memory is ordinary memory for Eva, read byte by byte, little-endian as on the
 * ATmega328P. Macros, as avr-libc's are, so that every translation unit Frama-C merges reads
 * the same definitions. */
#ifndef PROOF_AVR_PGMSPACE_H
#define PROOF_AVR_PGMSPACE_H
#include <stdint.h>
#include <string.h>

#define PROGMEM
#define PROOF_PGM_BYTE(p, k) ((uint32_t)((const uint8_t *)(p))[k])
#define pgm_read_byte(p) ((uint8_t)PROOF_PGM_BYTE(p, 0))
#define pgm_read_word(p) ((uint16_t)(PROOF_PGM_BYTE(p, 0) | (PROOF_PGM_BYTE(p, 1) << 8)))
#define pgm_read_dword(p) (PROOF_PGM_BYTE(p, 0) | (PROOF_PGM_BYTE(p, 1) << 8) | \
                           (PROOF_PGM_BYTE(p, 2) << 16) | (PROOF_PGM_BYTE(p, 3) << 24))
#define memcpy_P memcpy
#define memcmp_P memcmp
#endif
