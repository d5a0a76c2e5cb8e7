/* STAND-IN for Zephyr's <zephyr/bluetooth/addr.h>: bt_addr_le_t, BT_ADDR_LE_STR_LEN,
 * bt_addr_le_to_str. Not Zephyr. */
#ifndef FREEBOT_STANDIN_BT_ADDR_H
#define FREEBOT_STANDIN_BT_ADDR_H
#include <stddef.h>
#include <stdint.h>
#define BT_ADDR_LE_STR_LEN 30
typedef struct {
    uint8_t val[6];
} bt_addr_t;
typedef struct {
    uint8_t type;
    bt_addr_t a;
} bt_addr_le_t;
int bt_addr_le_to_str(const bt_addr_le_t *addr, char *str, size_t len);
#endif
