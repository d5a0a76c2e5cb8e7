/* Included before runtime_c/swarmvm_kilobot.c by the kilobot-glue-learned configuration
 * (prove.py): the declaration swarmvm_store.h makes only where __AVR__ is defined (the EEPROM
 * medium, avr-libc's), which Frama-C's build does not define; harness_kilobot.c defines it over
 * an array of unknown bytes. A stand-in for the proof, not avr-libc code. */
#include <stdint.h>
struct svm_store;
void svm_store_avr_eeprom(struct svm_store *store, uint16_t base, uint16_t slot_size);
