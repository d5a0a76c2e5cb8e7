/*
 * Power cuts during a save of the learned-parameter store (runtime_c/swarmvm_store.h). Test
 * code only.
 *
 * The medium is wrapped so that only its first `budget` operations (bytes written, slot
 * erases) take effect: the rest of the save is lost, as when the battery dies there, also in
 * the middle of a block write. For every cut
 * point k from 0 to past the whole save, with 0, 1 or 2 records saved before, the probe saves a
 * new record with budget k, then loads as a robot would after the restart, and prints one line
 * "cut MEDIUM PRIOR K OUTCOME", OUTCOME being new, old (the last record saved before), none (no
 * record: only when there was none before) or garbage. Then "rot OUTCOME": a byte of the newest
 * slot damaged, the load must fall back to the older record.
 *
 * Media: "eeprom" (byte writes; on the ATmega328P the real EEPROM through avr-libc, from
 * kilolib's first free address), and on a host also "flash" (erase to 0xFF, writes only clear
 * bits, as a CapBot's flash page) with write blocks of 1 and of 4 bytes ("flash4", the
 * nRF52840's word). On flash a write that is not whole aligned blocks, or that programs a byte
 * twice between erases, is counted and printed at the end ("misuse N").
 *
 * Built with -DPROBE_ZEPHYR (QEMU mps2-an386, tests/targets/capbot/test_capbot_store.py) the one medium
 * is "zephyr": the CapBot's binding (runtime_c/swarmvm_store_zephyr.c) over the Zephyr flash
 * map stand-in of firmware/capbot/flash_qemu.c, which cuts after flash_qemu_budget operations.
 */
#include <stdint.h>

#include "probe_io.h"
#include "swarmvm_store.h"

#define SLOT_SIZE 32u
#define SLOTS_BYTES (2u * SLOT_SIZE)

#ifndef PROBE_ZEPHYR
static uint16_t budget;         /* medium operations left before the cut; 0xFFFF: no cut */

static int spend(void)
{
    if (budget == 0u) {
        return 0;
    }
    if (budget != 0xFFFFu) {
        budget--;
    }
    return 1;
}

#endif

#ifdef PROBE_ZEPHYR
#include "swarmvm_store_zephyr.h"
extern uint32_t flash_qemu_budget, flash_qemu_misuse;
void flash_qemu_damage(uint16_t address);
static svm_store_zephyr_t zephyr;

static void set_budget(uint16_t k)
{
    flash_qemu_budget = k == 0xFFFFu ? UINT32_MAX : k;
}

static void erase_all(void)
{
    (void)flash_area_erase(zephyr.area, 0, 2u * zephyr.store.slot_size);
}
#else
static void set_budget(uint16_t k)
{
    budget = k;
}
#endif

#ifdef PROBE_ZEPHYR
#elif defined(__AVR__)
#include <avr/eeprom.h>
#include "swarmvm_kilobot_eeprom.h"
#define BASE SVM_KILOBOT_EEPROM_FREE

static uint8_t medium_read(void *ctx, uint16_t address)
{
    (void)ctx;
    return eeprom_read_byte((const uint8_t *)address);
}

static void medium_set(uint16_t address, uint8_t value)
{
    eeprom_update_byte((uint8_t *)address, value);
}
#else
#define BASE 16u
static uint8_t cells[BASE + SLOTS_BYTES];

static uint8_t medium_read(void *ctx, uint16_t address)
{
    (void)ctx;
    return cells[address];
}

static void medium_set(uint16_t address, uint8_t value)
{
    cells[address] = value;
}
#endif

#ifndef PROBE_ZEPHYR
static uint8_t is_flash, block = 1;
static uint8_t programmed[BASE + SLOTS_BYTES];      /* flash: written since the last erase */
static uint16_t misuse;

static int medium_write(void *ctx, uint16_t address, const uint8_t *data, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    if (is_flash && (address % block != 0u || length % block != 0u)) {
        misuse++;
    }
    for (i = 0; i < length; i++) {
        uint16_t at = (uint16_t)(address + i);
        if (spend()) {             /* after the cut nothing happens, misuse included */
            misuse = (uint16_t)(misuse + (is_flash && programmed[at]));
            medium_set(at, is_flash ? (uint8_t)(medium_read(0, at) & data[i]) : data[i]);
            programmed[at] = 1;
        }
    }
    return 0;
}

static int medium_erase(void *ctx, uint16_t address, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    if (spend()) {
        for (i = 0; i < length; i++) {
            medium_set((uint16_t)(address + i), 0xFFu);
            programmed[address + i] = 0;
        }
    }
    return 0;
}

static void erase_all(void)
{
    uint16_t i;
    for (i = 0; i < SLOTS_BYTES; i++) {
        medium_set((uint16_t)(BASE + i), 0xFFu);
        programmed[BASE + i] = 0;
    }
}
#endif

/* Record r: 4 + 4r bytes (r = 0, 1, 2 before, 3 the new one), each byte from r and its place. */
static uint8_t record(uint8_t r, uint8_t *out)
{
    uint8_t i, n = (uint8_t)(4u + 4u * r);
    for (i = 0; i < n; i++) {
        out[i] = (uint8_t)(r * 37u + i * 11u + 1u);
    }
    return n;
}

static uint8_t same(const uint8_t *a, const uint8_t *b, uint8_t n)
{
    uint8_t i;
    for (i = 0; i < n; i++) {
        if (a[i] != b[i]) {
            return 0;
        }
    }
    return 1;
}

/* What a load returns: "new" (record `fresh`), "old" (record `before`), "none" or "garbage". */
static const char *outcome(const svm_store_t *store, uint8_t fresh, int before)
{
    uint8_t got[SLOT_SIZE], want[SLOT_SIZE], n;
    int32_t length = svm_store_load(store, got, sizeof got, 0);
    if (length < 0) {
        return before < 0 ? "none" : "garbage";
    }
    n = record(fresh, want);
    if (length == n && same(got, want, n)) {
        return "new";
    }
    if (before >= 0) {
        n = record((uint8_t)before, want);
        if (length == n && same(got, want, n)) {
            return "old";
        }
    }
    return "garbage";
}

static void put_u8(uint8_t v)
{
    probe_putc((char)('0' + v / 10u));
    probe_putc((char)('0' + v % 10u));
}

/* Every cut point of a save of record 3 after `prior` records 0.. (lines "cut ..."). */
static void cuts(svm_store_t *store, const char *name)
{
    uint8_t prior, k, p, data[SLOT_SIZE], n, block = store->medium.block;
    uint8_t last = (uint8_t)(SVM_STORE_SLOT_BYTES(record(3, data), block) + 2u);
    for (prior = 0; prior < 3u; prior++) {
        for (k = 0; k <= last; k++) {     /* past the save's record + 10 operations */
            set_budget(0xFFFFu);
            erase_all();
            for (p = 0; p < prior; p++) {
                n = record(p, data);
                svm_store_save(store, data, n);
            }
            set_budget(k);
            n = record(3, data);
            svm_store_save(store, data, n);
            set_budget(0xFFFFu);
            probe_puts("cut ");
            probe_puts(name);
            probe_putc(' ');
            put_u8(prior);
            probe_putc(' ');
            put_u8(k);
            probe_putc(' ');
            probe_puts(outcome(store, 3, (int)prior - 1));
            probe_putc(' ');
            put_u8(block);
            probe_putc('\n');
        }
    }
}

static void finish(const svm_store_t *store, uint16_t misuse_count)
{
    probe_puts("rot ");
    probe_puts(outcome(store, 1, 0));
    probe_putc('\n');
    probe_puts("misuse ");
    put_u8((uint8_t)(misuse_count > 99u ? 99u : misuse_count));
    probe_putc('\n');
    probe_puts("end\n");
    probe_end();
}

/* Bit rot: records 0 then 1 (slot 1 the newest); then a byte of slot 1 is flipped. */
static void two_records(const svm_store_t *store)
{
    uint8_t data[SLOT_SIZE], n;
    set_budget(0xFFFFu);
    erase_all();
    n = record(0, data);
    svm_store_save(store, data, n);
    n = record(1, data);
    svm_store_save(store, data, n);
}

#ifdef PROBE_ZEPHYR
int main(void)
{
    probe_start();
    if (svm_store_zephyr_flash(&zephyr, FIXED_PARTITION_ID(storage_partition), SLOT_SIZE) != 0) {
        probe_puts("bind failed\n");
        return 1;
    }
    cuts(&zephyr.store, "zephyr");
    two_records(&zephyr.store);
    flash_qemu_damage((uint16_t)(zephyr.store.slot_size + 8u));
    finish(&zephyr.store, (uint16_t)flash_qemu_misuse);
    return 0;
}
#else
int main(void)
{
    svm_store_t store;
    probe_start();
    store.medium.read = medium_read;
    store.medium.write = medium_write;
    store.medium.erase = 0;
    store.medium.ctx = 0;
    store.medium.block = 1;
    store.base = BASE;
    store.slot_size = SLOT_SIZE;
    is_flash = 0;
    cuts(&store, "eeprom");
#ifndef __AVR__
    store.medium.erase = medium_erase;
    is_flash = 1;
    cuts(&store, "flash");
    store.medium.block = block = 4;
    cuts(&store, "flash4");
    store.medium.erase = 0;
    store.medium.block = block = 1;
    is_flash = 0;
#else
    (void)medium_erase;
#endif
    two_records(&store);
    medium_set((uint16_t)(BASE + SLOT_SIZE + 8u), (uint8_t)~medium_read(0, (uint16_t)(BASE + SLOT_SIZE + 8u)));
    finish(&store, misuse);
    return 0;
}
#endif
