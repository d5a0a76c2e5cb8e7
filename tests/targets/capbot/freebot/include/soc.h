/*
 * STAND-IN for the nRF52840's <soc.h> (Zephyr soc/nordic/nrf52): FreeBot's main.c includes it
 * but uses none of its names, so it is empty here. Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_SOC_H
#define FREEBOT_STANDIN_SOC_H
#endif
