/* STAND-IN for Zephyr's <zephyr/bluetooth/hci.h>: included by FreeBot's main.c, none of its names
 * used. Not Zephyr. */
#ifndef FREEBOT_STANDIN_BT_HCI_H
#define FREEBOT_STANDIN_BT_HCI_H
#include <zephyr/bluetooth/addr.h>
#endif
