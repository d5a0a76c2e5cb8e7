/*
 * The learned-parameter store (swarmvm_store.h) on a Zephyr flash partition: the CapBot's
 * binding (nRF52840: flash pages of 4 KB, programmed in aligned 32-bit words, 10,000 erases
 * per page). Through Zephyr's flash map API (<zephyr/storage/flash_map.h>: flash_area_open,
 * _read, _write, _erase, _align) and the page layout (<zephyr/drivers/flash.h>,
 * CONFIG_FLASH_PAGE_LAYOUT); prj.conf: CONFIG_FLASH=y, CONFIG_FLASH_MAP=y,
 * CONFIG_FLASH_PAGE_LAYOUT=y. The partition is the board's "storage_partition" unless the
 * application says otherwise (nRF52840 boards: 32 KB at 0xF8000, clear of the control-logic
 * page at 0xF3000).
 *
 * Each slot is a whole number of erase pages at the partition's start (slot 0, then slot 1),
 * so a save erases only its own slot's pages; the write block is the flash's (flash_area_align).
 */
#ifndef SWARMVM_STORE_ZEPHYR_H
#define SWARMVM_STORE_ZEPHYR_H

#include <stdint.h>

#include <zephyr/storage/flash_map.h>

#include "swarmvm_store.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct svm_store_zephyr {
    svm_store_t store;              /* give &z.store to svm_store_save / _load, svl_keeper_start */
    const struct flash_area *area;
} svm_store_zephyr_t;

/* Open flash area `area_id` (e.g. FIXED_PARTITION_ID(storage_partition)) for records of up to
 * `record_bytes`: 0, or a negative errno (the area's, or -EINVAL when the flash's write block
 * is over SVM_STORE_MAX_BLOCK, or -ENOSPC when two slots do not fit the partition or 64 KB). */
int svm_store_zephyr_flash(svm_store_zephyr_t *z, uint8_t area_id, uint16_t record_bytes);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_STORE_ZEPHYR_H */
