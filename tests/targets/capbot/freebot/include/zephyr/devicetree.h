/*
 * STAND-IN for Zephyr's <zephyr/devicetree.h>, the FreeBot board's devicetree reduced to the one
 * node main.c reads: DT_NODELABEL(sw2), a button on gpio0. Zephyr's real macros are generated
 * from the board's .dts; these are written by hand, with Zephyr's naming (DT_N_..._P_<prop>_...).
 * The pin number is this stand-in's, not the FreeBot's. Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_ZEPHYR_DEVICETREE_H
#define FREEBOT_STANDIN_ZEPHYR_DEVICETREE_H

#define DT_NODELABEL(label) DT_N_NODELABEL_##label
#define DT_N_NODELABEL_sw2_P_gpios_PIN 12
#define DT_N_NODELABEL_sw2_P_gpios_FLAGS 0x11     /* GPIO_ACTIVE_LOW | GPIO_PULL_UP */
#define DT_N_NODELABEL_sw2_P_gpios_CTLR z_dt_gpio0

#endif
