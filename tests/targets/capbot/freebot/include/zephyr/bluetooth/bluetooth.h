/*
 * STAND-IN for Zephyr's <zephyr/bluetooth/bluetooth.h>: bt_enable, advertising data
 * (struct bt_data, BT_DATA, BT_DATA_BYTES, BT_DATA_* and BT_LE_AD_* values) and
 * bt_le_adv_start with BT_LE_ADV_CONN, with Zephyr's signatures and values. Behaviour
 * (freebot_driver.c): enabling and advertising succeed. Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_BT_BLUETOOTH_H
#define FREEBOT_STANDIN_BT_BLUETOOTH_H

#include <stddef.h>
#include <stdint.h>
#include <zephyr/sys/util.h>
#include <zephyr/bluetooth/addr.h>
#include <zephyr/bluetooth/conn.h>

typedef void (*bt_ready_cb_t)(int err);
int bt_enable(bt_ready_cb_t cb);

#define BT_DATA_FLAGS 0x01
#define BT_DATA_UUID128_ALL 0x07
#define BT_DATA_NAME_COMPLETE 0x09
#define BT_LE_AD_GENERAL 0x02
#define BT_LE_AD_NO_BREDR 0x04

struct bt_data {
    uint8_t type;
    uint8_t data_len;
    const uint8_t *data;
};
#define BT_DATA(_type, _data, _data_len) {.type = (_type), .data_len = (_data_len), .data = (const uint8_t *)(_data)}
#define BT_DATA_BYTES(_type, ...) \
    BT_DATA(_type, ((uint8_t[]){__VA_ARGS__}), sizeof((uint8_t[]){__VA_ARGS__}))

struct bt_le_adv_param {
    uint8_t id;
    uint8_t sid;
    uint8_t secondary_max_skip;
    uint32_t options;
    uint32_t interval_min;
    uint32_t interval_max;
    const bt_addr_le_t *peer;
};
#define BT_LE_ADV_OPT_CONNECTABLE BIT(0)
#define BT_GAP_ADV_FAST_INT_MIN_2 0x00a0
#define BT_GAP_ADV_FAST_INT_MAX_2 0x00f0
#define BT_LE_ADV_PARAM(_options, _int_min, _int_max, _peer) \
    ((const struct bt_le_adv_param *)&(struct bt_le_adv_param){ \
        .id = 0, .sid = 0, .secondary_max_skip = 0, .options = (_options), \
        .interval_min = (_int_min), .interval_max = (_int_max), .peer = (_peer)})
#define BT_LE_ADV_CONN BT_LE_ADV_PARAM(BT_LE_ADV_OPT_CONNECTABLE, BT_GAP_ADV_FAST_INT_MIN_2, \
                                       BT_GAP_ADV_FAST_INT_MAX_2, NULL)

int bt_le_adv_start(const struct bt_le_adv_param *param, const struct bt_data *ad, size_t ad_len,
                    const struct bt_data *sd, size_t sd_len);

#endif
