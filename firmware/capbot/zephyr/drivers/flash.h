/*
 * STAND-IN, DECLARATIONS ONLY: the page-layout part of Zephyr's <zephyr/drivers/flash.h>
 * (CONFIG_FLASH_PAGE_LAYOUT) that runtime_c/swarmvm_store_zephyr.c uses, with Zephyr's names
 * and types. Not Zephyr; firmware/capbot/flash_qemu.c defines it for QEMU.
 */
#ifndef ZEPHYR_STANDIN_DRIVERS_FLASH_H
#define ZEPHYR_STANDIN_DRIVERS_FLASH_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

struct device;

struct flash_pages_info {
    off_t start_offset;     /* offset of the page from the start of the flash device */
    size_t size;
    uint32_t index;
};

int flash_get_page_info_by_offs(const struct device *dev, off_t offset, struct flash_pages_info *info);

#endif
