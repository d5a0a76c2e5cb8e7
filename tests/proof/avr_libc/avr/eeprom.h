/* Proof stand-in of avr-libc's <avr/eeprom.h> (tests/proof/avr_libc/README.md), not avr-libc
 * code: the two functions runtime_c/ calls, with contracts over one abstract cell that stands
 * for the whole EEPROM. An EEPROM address is not a RAM pointer, so the contracts require nothing
 * of it: a read gives a byte that depends on the address and the EEPROM, a write changes the
 * EEPROM. The address is an `indirect` dependency: it chooses the byte but is not part of its
 * value (a direct one would make Eva take every byte read for a mix of addresses). */
#ifndef PROOF_AVR_EEPROM_H
#define PROOF_AVR_EEPROM_H
#include <stdint.h>

extern volatile uint8_t proof_eeprom_cells;

/*@ assigns \result \from indirect: p, proof_eeprom_cells; */
uint8_t eeprom_read_byte(const uint8_t *p);

/*@ assigns proof_eeprom_cells \from indirect: p, value, proof_eeprom_cells; */
void eeprom_update_byte(uint8_t *p, uint8_t value);
#endif
