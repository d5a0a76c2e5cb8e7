/* STAND-IN for Zephyr's <zephyr/device.h>: struct device and DEVICE_DT_GET, for the FreeBot test.
 * Not Zephyr. */
#ifndef FREEBOT_STANDIN_ZEPHYR_DEVICE_H
#define FREEBOT_STANDIN_ZEPHYR_DEVICE_H
#include <stdbool.h>
struct device {
    const char *name;
};
bool device_is_ready(const struct device *dev);
#endif
