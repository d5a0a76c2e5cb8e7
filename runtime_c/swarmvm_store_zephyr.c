/* The learned-parameter store on a Zephyr flash partition (swarmvm_store_zephyr.h). */
#include "swarmvm_store_zephyr.h"

#include <errno.h>

#include <zephyr/drivers/flash.h>

static uint8_t area_read(void *ctx, uint16_t address)
{
    const svm_store_zephyr_t *z = (const svm_store_zephyr_t *)ctx;
    uint8_t value = SVM_STORE_EMPTY;     /* an unreadable byte reads as erased: no record */
    (void)flash_area_read(z->area, (off_t)address, &value, 1u);
    return value;
}

static int area_write(void *ctx, uint16_t address, const uint8_t *data, uint16_t length)
{
    const svm_store_zephyr_t *z = (const svm_store_zephyr_t *)ctx;
    return flash_area_write(z->area, (off_t)address, data, length);
}

static int area_erase(void *ctx, uint16_t address, uint16_t length)
{
    const svm_store_zephyr_t *z = (const svm_store_zephyr_t *)ctx;
    return flash_area_erase(z->area, (off_t)address, length);
}

int svm_store_zephyr_flash(svm_store_zephyr_t *z, uint8_t area_id, uint16_t record_bytes)
{
    struct flash_pages_info page;
    uint32_t block, slot;
    int err = flash_area_open(area_id, &z->area);
    if (err != 0) {
        return err;
    }
    block = flash_area_align(z->area);
    if (block == 0u || block > SVM_STORE_MAX_BLOCK) {
        return -EINVAL;
    }
    err = flash_get_page_info_by_offs(z->area->fa_dev, z->area->fa_off, &page);
    if (err != 0) {
        return err;
    }
    slot = SVM_STORE_SLOT_BYTES((uint32_t)record_bytes, block);
    slot = (slot + page.size - 1u) / page.size * page.size;
    if (2u * slot > z->area->fa_size || 2u * slot > 0xFFFFu) {
        return -ENOSPC;
    }
    z->store.medium.read = area_read;
    z->store.medium.write = area_write;
    z->store.medium.erase = area_erase;
    z->store.medium.ctx = z;
    z->store.medium.block = (uint8_t)block;
    z->store.base = 0;
    z->store.slot_size = (uint16_t)slot;
    return 0;
}
