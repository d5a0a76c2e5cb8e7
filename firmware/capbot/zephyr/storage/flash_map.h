/*
 * STAND-IN, DECLARATIONS ONLY: the part of Zephyr's <zephyr/storage/flash_map.h> that
 * runtime_c/swarmvm_store_zephyr.c uses, with Zephyr's names, types and return conventions
 * (0 or a negative errno), so that it builds and runs without the nRF Connect SDK. Not Zephyr;
 * the real build uses Zephyr's header. firmware/capbot/flash_qemu.c defines these functions
 * for QEMU on a simulated NOR flash partition.
 */
#ifndef ZEPHYR_STANDIN_FLASH_MAP_H
#define ZEPHYR_STANDIN_FLASH_MAP_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>      /* off_t, as Zephyr's header gets it */

struct device;

/* A fixed flash partition (Zephyr: from the devicetree's fixed-partitions). */
struct flash_area {
    uint8_t fa_id;
    uint8_t fa_device_id;
    uint16_t pad16;
    off_t fa_off;
    size_t fa_size;
    const struct device *fa_dev;
};

/* Zephyr: DT_FIXED_PARTITION_ID(DT_NODELABEL(label)), the partition's id in the devicetree.
 * The stand-in knows one partition, the nRF52840 boards' "storage_partition". */
#define FIXED_PARTITION_ID(label) FLASH_STANDIN_ID_##label
#define FLASH_STANDIN_ID_storage_partition 3

int flash_area_open(uint8_t id, const struct flash_area **fa);
void flash_area_close(const struct flash_area *fa);
int flash_area_read(const struct flash_area *fa, off_t off, void *dst, size_t len);
int flash_area_write(const struct flash_area *fa, off_t off, const void *src, size_t len);
int flash_area_erase(const struct flash_area *fa, off_t off, size_t len);
uint32_t flash_area_align(const struct flash_area *fa);

#endif
