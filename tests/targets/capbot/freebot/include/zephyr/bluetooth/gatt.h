/* STAND-IN for Zephyr's <zephyr/bluetooth/gatt.h>: FreeBot's main.c includes it and uses none of
 * its names directly (the NUS service does). Not Zephyr. */
#ifndef FREEBOT_STANDIN_BT_GATT_H
#define FREEBOT_STANDIN_BT_GATT_H
#include <zephyr/bluetooth/conn.h>
#include <zephyr/bluetooth/uuid.h>
#endif
