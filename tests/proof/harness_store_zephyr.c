/* Eva harness over runtime_c/swarmvm_store_zephyr.c, the CapBot's store of learned parameters on a
 * Zephyr flash partition (with swarmvm_store.c and swarmvm.c's svm_crc16_update; make prove;
 * docs/proof.md).
 *
 * Zephyr's flash map and page-layout calls (firmware/capbot/zephyr/'s declarations, the stand-in
 * headers of the QEMU build, with Zephyr's names, types and return conventions) are defined here
 * as Zephyr documents them, over a partition of unknown bytes: flash_area_open succeeds or not
 * (an unknown 0 or -ENOENT) and gives a partition of an unknown offset and size 0 ..
 * PROOF_PARTITION; flash_area_align an unknown write block 0 .. 255 (svm_store_zephyr_flash
 * refuses all but 1 .. SVM_STORE_MAX_BLOCK); flash_get_page_info_by_offs fails or not and gives
 * pages of an unknown size 1 .. PROOF_PAGE (a flash device has pages of at least a byte); reads,
 * writes and erases outside the partition are refused with -EINVAL, as Zephyr's are, and inside
 * it read, write or erase its bytes, a write or an erase failing or not (an unknown answer). The
 * record size is unknown 0 .. 65535. On an accepted partition, a loop of an unknown number of
 * iterations (Eva widens it), each a save of PROOF_PAYLOAD unknown bytes of an unknown length, a
 * load into a buffer of an unknown capacity and, at any iteration, the partition's bytes changed
 * to any values (a cut, rot). */
#include <errno.h>
#include "__fc_builtin.h"
#include "swarmvm_store_zephyr.h"
#include <zephyr/drivers/flash.h>

void Frama_C_show_each_reached(void);

#define PROOF_PARTITION 8192u   /* the partition's size, at most (the nRF52840's storage: 32 KB) */
#define PROOF_PAGE 65536u       /* a flash page's size, at most (the nRF52840's: 4096) */
#define PROOF_PAYLOAD 1025u

static uint8_t partition[PROOF_PARTITION];
static struct flash_area area;
static svm_store_zephyr_t z;
static uint8_t data[PROOF_PAYLOAD];

/* The end of [off, off + len) when it is inside the partition, as Zephyr's flash map checks
 * it, else 0 (the call is refused). The callers walk the bytes up to it one by one, testing the
 * partition's size too (implied by the end: spelt out, so that Eva sees each index below it). */
static size_t end_inside(const struct flash_area *fa, off_t off, size_t len)
{
    return off >= 0 && (size_t)off <= fa->fa_size && len != 0u && len <= fa->fa_size - (size_t)off
           ? (size_t)off + len : 0u;
}

int flash_area_open(uint8_t id, const struct flash_area **fa)
{
    (void)id;
    if (Frama_C_nondet(0, 1)) {
        return -ENOENT;
    }
    area.fa_off = (off_t)Frama_C_interval(0, 0x100000);
    area.fa_size = (size_t)Frama_C_interval(0, PROOF_PARTITION);
    area.fa_dev = 0;
    *fa = &area;
    return 0;
}

uint32_t flash_area_align(const struct flash_area *fa)
{
    (void)fa;
    return (uint32_t)Frama_C_interval(0, 255);
}

int flash_get_page_info_by_offs(const struct device *dev, off_t offset, struct flash_pages_info *info)
{
    (void)dev;
    if (Frama_C_nondet(0, 1)) {
        return -EINVAL;
    }
    info->start_offset = offset;
    info->size = (size_t)Frama_C_interval(1, PROOF_PAGE);
    info->index = 0;
    return 0;
}

int flash_area_read(const struct flash_area *fa, off_t off, void *dst, size_t len)
{
    size_t end = end_inside(fa, off, len), at, i;
    if (end == 0u) {
        return len == 0u ? 0 : -EINVAL;
    }
    for (at = (size_t)off, i = 0; at < end && at < fa->fa_size && i < len; at++, i++) {
        ((uint8_t *)dst)[i] = partition[at];
    }
    return 0;
}

int flash_area_write(const struct flash_area *fa, off_t off, const void *src, size_t len)
{
    size_t end = end_inside(fa, off, len), at, i;
    if (end == 0u) {
        return len == 0u ? 0 : -EINVAL;
    }
    for (at = (size_t)off, i = 0; at < end && at < fa->fa_size && i < len; at++, i++) {
        partition[at] = ((const uint8_t *)src)[i];
    }
    return Frama_C_nondet(0, -EIO);
}

int flash_area_erase(const struct flash_area *fa, off_t off, size_t len)
{
    size_t end = end_inside(fa, off, len), at;
    if (end == 0u) {
        return len == 0u ? 0 : -EINVAL;
    }
    for (at = (size_t)off; at < end && at < fa->fa_size; at++) {
        partition[at] = SVM_STORE_EMPTY;
    }
    return Frama_C_nondet(0, -EIO);
}

int main(void)
{
    uint32_t sequence;
    Frama_C_make_unknown((char *)partition, sizeof partition);
    if (svm_store_zephyr_flash(&z, 3u, (uint16_t)Frama_C_interval(0, 65535)) != 0) {
        return 0;
    }
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        Frama_C_make_unknown((char *)data, sizeof data);
        (void)svm_store_save(&z.store, data, (uint16_t)Frama_C_interval(0, PROOF_PAYLOAD));
        (void)svm_store_load(&z.store, data, (uint16_t)Frama_C_interval(0, PROOF_PAYLOAD),
                             Frama_C_nondet(0, 1) ? &sequence : 0);
        if (Frama_C_nondet(0, 1)) {
            Frama_C_make_unknown((char *)partition, sizeof partition);
        }
    }
    return 0;
}
