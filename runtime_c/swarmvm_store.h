/*
 * swarmvm store: learned parameters kept across power cuts (Kilobot EEPROM, CapBot flash).
 *
 * A robot saves what it learned (svl_policy_save's words, a classifier's weights) while it runs;
 * the battery can die in the middle of that write. The store keeps two slots and writes the
 * new record into the slot that does not hold the newest one, so the newest complete record is
 * never overwritten. With the medium's write block B (1 for EEPROM; a flash's write-block
 * size, e.g. 4 on the nRF52840, whose flash programs whole aligned 32-bit words) a slot is
 *
 *   state (1 byte, padded with 0xFF to B) | sequence (u32 LE) | length (u16 LE) | payload
 *   | CRC-16 (u16 LE) | 0xFF padding to a multiple of B
 *
 * with the CRC (svm_crc16_update, the image's checksum) over sequence, length and payload. A
 * save first marks the slot empty (state SVM_STORE_EMPTY; on flash: erases the slot), then
 * writes sequence, length, payload and CRC, and only then the state block with the byte
 * SVM_STORE_COMMITTED. Every write is whole blocks at block-aligned addresses, each block
 * written once after the erase (flash allows no more). A write cut anywhere leaves the slot
 * empty or, once the commit byte is in, complete; the other slot still holds the previous
 * record. A load takes the committed slot with a good CRC and the newer sequence number
 * (serial-number order, so the counter may wrap): it returns the old or the new parameters
 * after a cut, never a mixture; a damaged slot (bit rot) is skipped.
 *
 * The medium is reached through three functions per platform (byte read, block write, and for
 * flash a slot erase): swarmvm_store.c holds the one implementation of the scheme for every
 * target; svm_store_avr_eeprom() binds the ATmega328P's EEPROM (avr-libc),
 * swarmvm_store_zephyr.c a CapBot's flash partition (Zephyr's flash_map API). C99, no heap.
 */
#ifndef SWARMVM_STORE_H
#define SWARMVM_STORE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SVM_STORE_EMPTY 0xFFu       /* an erased byte: no record */
#define SVM_STORE_COMMITTED 0x5Au   /* every other byte of the slot was written */
#define SVM_STORE_OVERHEAD 9u       /* state, sequence, length, CRC (write block 1) */

/* The largest write block a medium may have (bytes; a power of two). */
#ifndef SVM_STORE_MAX_BLOCK
#define SVM_STORE_MAX_BLOCK 8u
#endif

/* Bytes per slot for a payload of `payload` bytes on a medium with write block `block`. */
#define SVM_STORE_SLOT_BYTES(payload, block) \
    ((block) + (((payload) + 8u + (block) - 1u) / (block)) * (block))

/* The medium: read a byte; write `length` bytes (a multiple of `block`, at a multiple of
 * `block`; 0 on success); erase `length` bytes from `address` to SVM_STORE_EMPTY (flash
 * pages; null for a byte-writable medium such as EEPROM). */
typedef struct svm_store_medium {
    uint8_t (*read)(void *ctx, uint16_t address);
    int (*write)(void *ctx, uint16_t address, const uint8_t *data, uint16_t length);
    int (*erase)(void *ctx, uint16_t address, uint16_t length);
    void *ctx;
    uint8_t block;          /* write block: 1 (EEPROM) .. SVM_STORE_MAX_BLOCK, a power of two */
} svm_store_medium_t;

typedef struct svm_store {
    svm_store_medium_t medium;
    uint16_t base;          /* address of slot 0 (a multiple of the block); slot 1 follows */
    uint16_t slot_size;     /* bytes per slot: SVM_STORE_SLOT_BYTES(largest payload, block);
                             * on flash a whole number of erase pages */
} svm_store_t;

/* Write `length` bytes as the newest record: 0, or -1 when they do not fit a slot, the
 * block is not a power of two up to SVM_STORE_MAX_BLOCK, or the medium refused an erase or
 * a write (the previous record is still the newest then). */
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

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_STORE_H */
