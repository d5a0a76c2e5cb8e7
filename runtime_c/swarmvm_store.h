/*
 * swarmvm store: learned parameters kept across power cuts (Kilobot EEPROM, CapBot flash).
 *
 * A robot saves what it learned (svl_policy_save's words, a classifier's weights) while it runs;
 * the battery can die in the middle of that write. The store keeps two slots and writes the
 * new record into the slot that does not hold the newest one, so the newest complete record is
 * never overwritten. A slot is
 *
 *   state (1 byte) | sequence (u32 LE) | length (u16 LE) | payload | CRC-16 (u16 LE)
 *
 * with the CRC (svm_crc16_update, the image's checksum) over sequence, length and payload. A
 * save first marks the slot empty (state SVM_STORE_EMPTY; on flash: erases the slot), then
 * writes sequence, length, payload and CRC, and only then the state byte SVM_STORE_COMMITTED.
 * A write cut anywhere leaves the slot empty or, once the last byte is in, complete; the other
 * slot still holds the previous record. A load takes the committed slot with a good CRC and
 * the newer sequence number (serial-number order, so the counter may wrap): it returns the old
 * or the new parameters after a cut, never a mixture; a damaged slot (bit rot) is skipped.
 *
 * The medium is reached through three functions per platform (byte read, byte write, and for
 * flash a slot erase): swarmvm_store.c holds the one implementation of the scheme for every
 * target; svm_store_avr_eeprom() binds the ATmega328P's EEPROM (avr-libc), a CapBot binds its
 * flash driver. C99, no heap.
 */
#ifndef SWARMVM_STORE_H
#define SWARMVM_STORE_H

#include <stdint.h>

#define SVM_STORE_EMPTY 0xFFu       /* an erased byte: no record */
#define SVM_STORE_COMMITTED 0x5Au   /* every other byte of the slot was written */
#define SVM_STORE_OVERHEAD 9u       /* state, sequence, length, CRC */

/* The medium: read a byte; write a byte (0 on success); erase `length` bytes from `address`
 * to SVM_STORE_EMPTY (flash pages; 0 for a byte-writable medium such as EEPROM). */
typedef struct svm_store_medium {
    uint8_t (*read)(void *ctx, uint16_t address);
    int (*write)(void *ctx, uint16_t address, uint8_t value);
    int (*erase)(void *ctx, uint16_t address, uint16_t length);
    void *ctx;
} svm_store_medium_t;

typedef struct svm_store {
    svm_store_medium_t medium;
    uint16_t base;          /* address of slot 0; slot 1 follows it */
    uint16_t slot_size;     /* bytes per slot: SVM_STORE_OVERHEAD + the largest payload */
} svm_store_t;

/* Write `length` bytes as the newest record: 0, or -1 when they do not fit a slot or the
 * medium refused a write (the previous record is still the newest then). */
int svm_store_save(const svm_store_t *store, const uint8_t *data, uint16_t length);

/* Copy the newest valid record into `data` (room for `cap` bytes): its length, or -1 when no
 * slot holds a valid record that fits (never saved, or both damaged). `sequence`, when not
 * null, receives its sequence number. */
int32_t svm_store_load(const svm_store_t *store, uint8_t *data, uint16_t cap, uint32_t *sequence);

#ifdef __AVR__
/* The store on the ATmega328P's EEPROM from `base` (on a Kilobot at or above
 * SVM_KILOBOT_EEPROM_FREE, swarmvm_kilobot_eeprom.h), two slots of `slot_size` bytes. */
void svm_store_avr_eeprom(svm_store_t *store, uint16_t base, uint16_t slot_size);
#endif

#endif /* SWARMVM_STORE_H */
