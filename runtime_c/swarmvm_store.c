/* swarmvm store: two-slot, power-cut-safe records of learned parameters (swarmvm_store.h). */
#include "swarmvm_store.h"

#include "swarmvm.h"

#ifdef __AVR__
#include <avr/eeprom.h>
#endif

/* Offsets in a slot: the state byte, then from one write block on the body. */
#define AT_STATE 0u
#define BODY_SEQUENCE 0u
#define BODY_LENGTH 4u
#define BODY_PAYLOAD 6u
#define BODY_FIXED 8u           /* sequence, length, CRC */

static uint16_t slot_at(const svm_store_t *store, uint8_t slot)
{
    return (uint16_t)(store->base + (uint16_t)(slot * store->slot_size));
}

static uint16_t body_at(const svm_store_t *store, uint8_t slot)
{
    return (uint16_t)(slot_at(store, slot) + store->medium.block);
}

/* The medium's write block (1 .. SVM_STORE_MAX_BLOCK, a power of two) when a payload of
 * `length` bytes fits a slot written in such blocks; 0 when the block is unusable or the payload
 * does not fit. */
static uint8_t fitting_block(const svm_store_t *store, uint16_t length)
{
    uint8_t block = store->medium.block;
    if (block == 0u || block > SVM_STORE_MAX_BLOCK || (block & (block - 1u)) != 0u
        || store->slot_size < block + BODY_FIXED || length > store->slot_size - block - BODY_FIXED
        || (uint32_t)block + ((uint32_t)length + BODY_FIXED + block - 1u) / block * block > store->slot_size) {
        return 0;
    }
    return block;
}

static uint16_t read16(const svm_store_t *store, uint16_t at)
{
    const svm_store_medium_t *m = &store->medium;
    return (uint16_t)(m->read(m->ctx, at) | (uint16_t)m->read(m->ctx, (uint16_t)(at + 1u)) << 8);
}

/* A slot's record when it is committed, fits the slot and its CRC agrees: 0 and its sequence
 * and length; -1 otherwise. */
static int check_slot(const svm_store_t *store, uint8_t slot, uint32_t *sequence, uint16_t *length)
{
    const svm_store_medium_t *m = &store->medium;
    uint16_t at = body_at(store, slot), crc = SVM_CRC16_INIT, i, end;
    if (m->read(m->ctx, (uint16_t)(slot_at(store, slot) + AT_STATE)) != SVM_STORE_COMMITTED) {
        return -1;
    }
    *length = read16(store, (uint16_t)(at + BODY_LENGTH));
    if (fitting_block(store, *length) == 0u) {
        return -1;
    }
    end = (uint16_t)(BODY_PAYLOAD + *length);
    for (i = BODY_SEQUENCE; i < end; i++) {
        crc = svm_crc16_update(crc, m->read(m->ctx, (uint16_t)(at + i)));
    }
    if (crc != read16(store, (uint16_t)(at + end))) {
        return -1;
    }
    *sequence = (uint32_t)read16(store, (uint16_t)(at + BODY_SEQUENCE))
                | ((uint32_t)read16(store, (uint16_t)(at + BODY_SEQUENCE + 2u)) << 16);
    return 0;
}

/* The slot of the newest valid record (serial-number order), or -1. */
static int newest(const svm_store_t *store, uint32_t *sequence, uint16_t *length)
{
    uint32_t seq1;
    uint16_t len1;
    int ok0 = check_slot(store, 0, sequence, length) == 0;
    int ok1 = check_slot(store, 1, &seq1, &len1) == 0;
    if (ok1 && (!ok0 || (int32_t)(seq1 - *sequence) > 0)) {
        *sequence = seq1;
        *length = len1;
        return 1;
    }
    return ok0 ? 0 : -1;
}

/* Byte i of a record's body: sequence, length, payload, CRC, then 0xFF padding. The CRC is
 * final once the payload's last byte went through `crc` (bodies are produced in order). Kept out
 * of its one caller's loop: inlined there, avr-gcc -O3 (the Kilobot's LEARNED=1 build) unrolls
 * the pair into 900 more bytes. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static uint8_t body_byte(uint16_t i, uint32_t sequence, const uint8_t *data, uint16_t length, uint16_t *crc)
{
    uint8_t byte;
    if (i < BODY_PAYLOAD + length + 2u && i >= BODY_PAYLOAD + length) {
        return (uint8_t)(i != BODY_PAYLOAD + length ? *crc >> 8 : *crc);    /* low byte, then high */
    }
    if (i >= BODY_PAYLOAD + length) {
        return SVM_STORE_EMPTY;
    }
    if (i < BODY_LENGTH) {
        byte = (uint8_t)(sequence >> (8u * i));
    } else if (i < BODY_PAYLOAD) {
        byte = (uint8_t)(length >> (8u * (i - BODY_LENGTH)));
    } else {
        byte = data[i - BODY_PAYLOAD];
    }
    *crc = svm_crc16_update(*crc, byte);
    return byte;
}

int svm_store_save(const svm_store_t *store, const uint8_t *data, uint16_t length)
{
    const svm_store_medium_t *m = &store->medium;
    uint32_t sequence = 0;
    uint16_t old_length, at, body, end, crc = SVM_CRC16_INIT, i;
    uint8_t block[SVM_STORE_MAX_BLOCK], b, slot_block = fitting_block(store, length);
    int slot;
    if (slot_block == 0u) {
        return -1;
    }
    slot = newest(store, &sequence, &old_length);
    sequence = slot < 0 ? 0u : sequence + 1u;
    slot = slot == 0 ? 1 : 0;
    at = slot_at(store, (uint8_t)slot);
    body = body_at(store, (uint8_t)slot);
    for (b = 0; b < SVM_STORE_MAX_BLOCK; b++) {     /* the whole buffer: each write reads a prefix */
        block[b] = SVM_STORE_EMPTY;
    }
    /* 1. The target slot holds no record from here until its state byte is written last. */
    if (m->erase != 0 ? m->erase(m->ctx, at, store->slot_size) : m->write(m->ctx, at, block, slot_block)) {
        return -1;
    }
    /* 2. Sequence, length, payload, CRC: whole blocks, each written once. */
    end = (uint16_t)((BODY_FIXED + length + slot_block - 1u) / slot_block * slot_block);
    for (i = 0; i < end; i = (uint16_t)(i + slot_block)) {
        for (b = 0; b < slot_block; b++) {
            block[b] = body_byte((uint16_t)(i + b), sequence, data, length, &crc);
        }
        if (m->write(m->ctx, (uint16_t)(body + i), block, slot_block)) {
            return -1;
        }
    }
    /* 3. Commit: the state block, its first byte the mark, so the record is there whole or not
     * at all. */
    block[0] = SVM_STORE_COMMITTED;
    for (b = 1; b < slot_block; b++) {
        block[b] = SVM_STORE_EMPTY;
    }
    return m->write(m->ctx, (uint16_t)(at + AT_STATE), block, slot_block) ? -1 : 0;
}

int32_t svm_store_load(const svm_store_t *store, uint8_t *data, uint16_t cap, uint32_t *sequence)
{
    const svm_store_medium_t *m = &store->medium;
    uint32_t seq = 0;
    uint16_t length = 0, at, i;
    int slot = newest(store, &seq, &length);
    if (slot < 0 || length > cap) {
        return -1;
    }
    at = (uint16_t)(body_at(store, (uint8_t)slot) + BODY_PAYLOAD);
    for (i = 0; i < length; i++) {
        data[i] = m->read(m->ctx, (uint16_t)(at + i));
    }
    if (sequence != 0) {
        *sequence = seq;
    }
    return (int32_t)length;
}

#ifdef __AVR__
static uint8_t eeprom_read(void *ctx, uint16_t address)
{
    (void)ctx;
    return eeprom_read_byte((const uint8_t *)address);
}

/* eeprom_update_byte skips a byte that already holds the value: no wear for an unchanged
 * parameter. */
static int eeprom_write(void *ctx, uint16_t address, const uint8_t *data, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    for (i = 0; i < length; i++) {
        eeprom_update_byte((uint8_t *)(address + i), data[i]);
    }
    return 0;
}

void svm_store_avr_eeprom(svm_store_t *store, uint16_t base, uint16_t slot_size)
{
    store->medium.read = eeprom_read;
    store->medium.write = eeprom_write;
    store->medium.erase = 0;
    store->medium.ctx = 0;
    store->medium.block = 1;
    store->base = base;
    store->slot_size = slot_size;
}
#endif
