/* Proof stand-in of avr-libc's <util/crc16.h> (tests/proof/avr_libc/README.md), not avr-libc
 * code: _crc_ccitt_update in the C form avr-libc's manual gives for its assembly (CRC-CCITT,
 * reflected polynomial 0x8408, one byte). */
#ifndef PROOF_UTIL_CRC16_H
#define PROOF_UTIL_CRC16_H
#include <stdint.h>
//@ assigns \nothing;
static inline uint16_t _crc_ccitt_update(uint16_t crc, uint8_t data)
{
    data = (uint8_t)(data ^ (uint8_t)crc);
    data = (uint8_t)(data ^ (uint8_t)(data << 4));
    return (uint16_t)((((uint16_t)data << 8) | (uint8_t)(crc >> 8)) ^ (uint8_t)(data >> 4) ^ ((uint16_t)data << 3));
}
#endif
