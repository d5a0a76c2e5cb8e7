/* STAND-IN for Zephyr's <zephyr/usb/usb_device.h> (usb_enable); FreeBot's main.c includes it and
 * calls nothing from it. Not Zephyr. */
#ifndef FREEBOT_STANDIN_USB_DEVICE_H
#define FREEBOT_STANDIN_USB_DEVICE_H
#include <stdint.h>
enum usb_dc_status_code { USB_DC_ERROR, USB_DC_RESET, USB_DC_CONNECTED, USB_DC_CONFIGURED, USB_DC_DISCONNECTED };
typedef void (*usb_dc_status_callback)(enum usb_dc_status_code cb_status, const uint8_t *param);
int usb_enable(usb_dc_status_callback status_cb);
#endif
