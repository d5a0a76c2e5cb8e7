/* STAND-IN for Zephyr's <zephyr/bluetooth/uuid.h>: BT_UUID_128_ENCODE, Zephyr's little-endian
 * byte list of a 128-bit UUID. Not Zephyr. */
#ifndef FREEBOT_STANDIN_BT_UUID_H
#define FREEBOT_STANDIN_BT_UUID_H
#define BT_UUID_128_ENCODE(w32, w1, w2, w3, w48) \
    (((w48) >> 0) & 0xFF), (((w48) >> 8) & 0xFF), (((w48) >> 16) & 0xFF), (((w48) >> 24) & 0xFF), \
    (((w48) >> 32) & 0xFF), (((w48) >> 40) & 0xFF), (((w3) >> 0) & 0xFF), (((w3) >> 8) & 0xFF), \
    (((w2) >> 0) & 0xFF), (((w2) >> 8) & 0xFF), (((w1) >> 0) & 0xFF), (((w1) >> 8) & 0xFF), \
    (((w32) >> 0) & 0xFF), (((w32) >> 8) & 0xFF), (((w32) >> 16) & 0xFF), (((w32) >> 24) & 0xFF)
#endif
