/* swarmvm store: two-slot, power-cut-safe records of learned parameters (swarmvm_store.h). */
#include "swarmvm_store.h"

#include "swarmvm.h"

#ifdef __AVR__
#include <avr/eeprom.h>
#endif

#define AT_STATE 0u
#define AT_SEQUENCE 1u
#define AT_LENGTH 5u
#define AT_PAYLOAD 7u

static uint16_t slot_at(const svm_store_t *store, uint8_t slot)
{
    return (uint16_t)(store->base + (uint16_t)(slot * store->slot_size));
}

static uint16_t read16(const svm_store_t *store, uint16_t at)
{
    const svm_store_medium_t *m = &store->medium;
    return (uint16_t)(m->read(m->ctx, at) | (uint16_t)(m->read(m->ctx, (uint16_t)(at + 1u)) << 8));
}

/* A slot's record when it is committed, fits the slot and its CRC agrees: 0 and its sequence
 * and length; -1 otherwise. */
static int check_slot(const svm_store_t *store, uint8_t slot, uint32_t *sequence, uint16_t *length)
{
    const svm_store_medium_t *m = &store->medium;
    uint16_t at = slot_at(store, slot), crc = SVM_CRC16_INIT, i, end;
    if (m->read(m->ctx, at) != SVM_STORE_COMMITTED) {
        return -1;
    }
    *length = read16(store, (uint16_t)(at + AT_LENGTH));
    if (*length > store->slot_size - SVM_STORE_OVERHEAD) {
        return -1;
    }
    end = (uint16_t)(AT_PAYLOAD + *length);
    for (i = AT_SEQUENCE; i < end; i++) {
        crc = svm_crc16_update(crc, m->read(m->ctx, (uint16_t)(at + i)));
    }
    if (crc != read16(store, (uint16_t)(at + end))) {
        return -1;
    }
    *sequence = (uint32_t)read16(store, (uint16_t)(at + AT_SEQUENCE))
                | ((uint32_t)read16(store, (uint16_t)(at + AT_SEQUENCE + 2u)) << 16);
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

int svm_store_save(const svm_store_t *store, const uint8_t *data, uint16_t length)
{
    const svm_store_medium_t *m = &store->medium;
    uint32_t sequence = 0;
    uint16_t old_length, at, crc = SVM_CRC16_INIT, i;
    uint8_t header[AT_PAYLOAD - AT_SEQUENCE];
    int slot;
    if (store->slot_size < SVM_STORE_OVERHEAD || length > store->slot_size - SVM_STORE_OVERHEAD) {
        return -1;
    }
    slot = newest(store, &sequence, &old_length);
    sequence = slot < 0 ? 0u : sequence + 1u;
    at = slot_at(store, (uint8_t)(slot == 0 ? 1 : 0));
    /* 1. The target slot holds no record from here until its state byte is written last. */
    if (m->erase != 0 ? m->erase(m->ctx, at, store->slot_size) : m->write(m->ctx, at, SVM_STORE_EMPTY)) {
        return -1;
    }
    for (i = 0; i < 4u; i++) {
        header[i] = (uint8_t)(sequence >> (8u * i));
    }
    header[4] = (uint8_t)length;
    header[5] = (uint8_t)(length >> 8);
    /* 2. Sequence, length, payload, CRC. */
    for (i = 0; i < sizeof header; i++) {
        crc = svm_crc16_update(crc, header[i]);
        if (m->write(m->ctx, (uint16_t)(at + AT_SEQUENCE + i), header[i])) {
            return -1;
        }
    }
    for (i = 0; i < length; i++) {
        crc = svm_crc16_update(crc, data[i]);
        if (m->write(m->ctx, (uint16_t)(at + AT_PAYLOAD + i), data[i])) {
            return -1;
        }
    }
    if (m->write(m->ctx, (uint16_t)(at + AT_PAYLOAD + length), (uint8_t)crc)
        || m->write(m->ctx, (uint16_t)(at + AT_PAYLOAD + length + 1u), (uint8_t)(crc >> 8))) {
        return -1;
    }
    /* 3. Commit: one byte, so the record is there whole or not at all. */
    return m->write(m->ctx, at, SVM_STORE_COMMITTED) ? -1 : 0;
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
    at = (uint16_t)(slot_at(store, (uint8_t)slot) + AT_PAYLOAD);
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

static int eeprom_write(void *ctx, uint16_t address, uint8_t value)
{
    (void)ctx;
    eeprom_update_byte((uint8_t *)address, value);
    return 0;
}

void svm_store_avr_eeprom(svm_store_t *store, uint16_t base, uint16_t slot_size)
{
    store->medium.read = eeprom_read;
    store->medium.write = eeprom_write;
    store->medium.erase = 0;
    store->medium.ctx = 0;
    store->base = base;
    store->slot_size = slot_size;
}
#endif
