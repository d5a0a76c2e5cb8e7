/*
 * QEMU definitions of the Zephyr flash map stand-in (zephyr/storage/flash_map.h,
 * zephyr/drivers/flash.h): the nRF52840's "storage_partition" (32 KB at 0xF8000, pages of
 * 4 KB, write block 4) simulated as NOR flash in RAM, with the nRF flash driver's rules: an
 * erase takes whole aligned pages and sets them to 0xFF; a write takes whole aligned 32-bit
 * words and can only clear bits; out of range or unaligned is -EINVAL. Not a driver: for the
 * store's power-cut test (tests/targets/capbot/test_capbot_store.py), it also stops doing anything
 * after flash_qemu_budget operations (bytes programmed, page erases) as a power cut would,
 * and counts a word programmed twice between erases (the nRF52840 allows it a limited number
 * of times only) in flash_qemu_misuse.
 */
#include <errno.h>
#include <string.h>

#include <zephyr/drivers/flash.h>
#include <zephyr/storage/flash_map.h>

#define PARTITION_OFFSET 0xF8000
#define PARTITION_SIZE 0x8000u
#define PAGE 4096u
#define WORD 4u

uint32_t flash_qemu_budget = UINT32_MAX;    /* operations left; UINT32_MAX: no cut */
uint32_t flash_qemu_misuse;
static uint8_t cells[PARTITION_SIZE];
static uint8_t programmed[PARTITION_SIZE / WORD];
static uint8_t opened;
static const struct flash_area storage = {FLASH_STANDIN_ID_storage_partition, 0, 0, PARTITION_OFFSET,
                                          PARTITION_SIZE, 0};

static int spend(void)
{
    if (flash_qemu_budget == 0u) {
        return 0;
    }
    if (flash_qemu_budget != UINT32_MAX) {
        flash_qemu_budget--;
    }
    return 1;
}

static int in_range(const struct flash_area *fa, off_t off, size_t len)
{
    return fa == &storage && opened && off >= 0 && (size_t)off <= PARTITION_SIZE && len <= PARTITION_SIZE - (size_t)off;
}

int flash_area_open(uint8_t id, const struct flash_area **fa)
{
    if (id != FLASH_STANDIN_ID_storage_partition) {
        return -ENOENT;
    }
    if (!opened) {
        memset(cells, 0xFF, sizeof cells);      /* a new robot's partition is erased */
        opened = 1;
    }
    *fa = &storage;
    return 0;
}

void flash_area_close(const struct flash_area *fa)
{
    (void)fa;
}

int flash_area_read(const struct flash_area *fa, off_t off, void *dst, size_t len)
{
    if (!in_range(fa, off, len)) {
        return -EINVAL;
    }
    memcpy(dst, &cells[(size_t)off], len);
    return 0;
}

int flash_area_write(const struct flash_area *fa, off_t off, const void *src, size_t len)
{
    const uint8_t *bytes = (const uint8_t *)src;
    size_t i;
    if (!in_range(fa, off, len) || (size_t)off % WORD != 0u || len % WORD != 0u) {
        return -EINVAL;
    }
    for (i = 0; i < len; i++) {
        size_t at = (size_t)off + i;
        if (!spend()) {
            return 0;               /* the power is gone: nothing more happens */
        }
        if (at % WORD == 0u) {
            flash_qemu_misuse += programmed[at / WORD];
            programmed[at / WORD] = 1;
        }
        cells[at] &= bytes[i];
    }
    return 0;
}

int flash_area_erase(const struct flash_area *fa, off_t off, size_t len)
{
    if (!in_range(fa, off, len) || (size_t)off % PAGE != 0u || len % PAGE != 0u) {
        return -EINVAL;
    }
    if (spend()) {
        memset(&cells[(size_t)off], 0xFF, len);
        memset(&programmed[(size_t)off / WORD], 0, len / WORD);
    }
    return 0;
}

uint32_t flash_area_align(const struct flash_area *fa)
{
    (void)fa;
    return WORD;
}

int flash_get_page_info_by_offs(const struct device *dev, off_t offset, struct flash_pages_info *info)
{
    (void)dev;
    if (offset < PARTITION_OFFSET || offset >= PARTITION_OFFSET + (off_t)PARTITION_SIZE) {
        return -EINVAL;
    }
    info->start_offset = offset / (off_t)PAGE * (off_t)PAGE;
    info->size = PAGE;
    info->index = (uint32_t)(offset / (off_t)PAGE);
    return 0;
}

/* Test only: flip a byte, as bit rot would. */
void flash_qemu_damage(uint16_t address)
{
    cells[address] = (uint8_t)~cells[address];
}
