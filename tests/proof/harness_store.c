/* Eva harness over runtime_c/swarmvm_store.c, the two-slot store of learned parameters (with
 * swarmvm.c's svm_crc16_update; make prove; docs/proof.md).
 *
 * The medium: PROOF_MEDIUM bytes of unknown values (any record an earlier run, a write cut by a
 * power loss or bit rot left), exactly room for two slots of the largest size PROOF_SLOT from the
 * highest base PROOF_BASE, so that an address past the two slots the store may use is a read or
 * write outside the array (one past the caller's slots but inside the array is not: Eva does not
 * relate the address to the unknown base and size); a write or an erase refused or not (an
 * unknown answer); an unknown write block 0 .. 255 (the store refuses all but 1, 2, 4, 8), with or
 * without an erase function (flash, EEPROM); an unknown slot size 0 .. PROOF_SLOT and base
 * 0 .. PROOF_BASE (a multiple of the block, as swarmvm_store.h asks of its caller). Then a loop
 * of an unknown number of iterations (Eva widens it), each: a save of PROOF_PAYLOAD unknown bytes
 * of an unknown length 0 .. PROOF_PAYLOAD (more than a slot holds: refused), a load into a buffer
 * of an unknown capacity 0 .. PROOF_PAYLOAD, and at any iteration the medium's bytes changed to
 * any values (a cut, rot). */
#include "__fc_builtin.h"
#include "swarmvm_store.h"

void Frama_C_show_each_reached(void);

#define PROOF_BASE 256u        /* the first slot's address, at most (the Kilobot's: 0xB2) */
#define PROOF_SLOT 640u        /* a slot's size, at most */
#define PROOF_MEDIUM (PROOF_BASE + 2u * PROOF_SLOT)
#define PROOF_PAYLOAD (PROOF_SLOT + 1u)

static uint8_t medium[PROOF_MEDIUM];
static svm_store_t store;
static uint8_t saved[PROOF_PAYLOAD];

static uint8_t read(void *ctx, uint16_t address)
{
    (void)ctx;
    return medium[address];
}

static int write(void *ctx, uint16_t address, const uint8_t *bytes, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    for (i = 0; i < length; i++) {
        medium[address + i] = bytes[i];
    }
    return Frama_C_interval(0, 1);
}

static int erase(void *ctx, uint16_t address, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    for (i = 0; i < length; i++) {
        medium[address + i] = SVM_STORE_EMPTY;
    }
    return Frama_C_interval(0, 1);
}

int main(void)
{
    uint32_t sequence;
    uint16_t block = (uint16_t)Frama_C_interval(0, 255), slot_size, base;
    Frama_C_make_unknown((char *)medium, sizeof medium);
    store.medium.read = read;
    store.medium.write = write;
    store.medium.erase = Frama_C_nondet(0, 1) ? erase : 0;
    store.medium.ctx = 0;
    store.medium.block = (uint8_t)block;
    slot_size = (uint16_t)Frama_C_interval(0, PROOF_SLOT);
    base = (uint16_t)Frama_C_interval(0, PROOF_BASE);
    if (block != 0u) {
        base = (uint16_t)(base / block * block);
    }
    store.base = base;
    store.slot_size = slot_size;
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        Frama_C_make_unknown((char *)saved, sizeof saved);
        (void)svm_store_save(&store, saved, (uint16_t)Frama_C_interval(0, PROOF_PAYLOAD));
        (void)svm_store_load(&store, saved, (uint16_t)Frama_C_interval(0, PROOF_PAYLOAD),
                             Frama_C_nondet(0, 1) ? &sequence : 0);
        if (Frama_C_nondet(0, 1)) {
            Frama_C_make_unknown((char *)medium, sizeof medium);
        }
    }
    return 0;
}
