/*
 * STAND-IN for the nRF Connect SDK's <bluetooth/services/nus.h> (Nordic UART Service), with its
 * signatures: bt_nus_init registers the callbacks, bt_nus_send sends. Behaviour
 * (freebot_driver.c): the test driver plays the phone, delivering the event script's messages to
 * the registered `received` callback, and logs what the program sends. Not the nRF Connect SDK.
 */
#ifndef FREEBOT_STANDIN_BT_NUS_H
#define FREEBOT_STANDIN_BT_NUS_H

#include <stdint.h>
#include <zephyr/bluetooth/conn.h>
#include <zephyr/bluetooth/uuid.h>

#define BT_UUID_NUS_VAL BT_UUID_128_ENCODE(0x6e400001, 0xb5a3, 0xf393, 0xe0a9, 0xe50e24dcca9eULL)

enum bt_nus_send_status { BT_NUS_SEND_STATUS_ENABLED, BT_NUS_SEND_STATUS_DISABLED };

struct bt_nus_cb {
    void (*received)(struct bt_conn *conn, const uint8_t *const data, uint16_t len);
    void (*sent)(struct bt_conn *conn);
    void (*send_enabled)(enum bt_nus_send_status status);
};

int bt_nus_init(struct bt_nus_cb *callbacks);
int bt_nus_send(struct bt_conn *conn, const uint8_t *data, uint16_t len);

#endif
