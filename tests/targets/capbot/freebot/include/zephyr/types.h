/* STAND-IN for Zephyr's <zephyr/types.h> (the C99 fixed-width types), for the FreeBot test
 * (tests/targets/capbot/test_freebot_main.py). Not Zephyr. */
#ifndef FREEBOT_STANDIN_ZEPHYR_TYPES_H
#define FREEBOT_STANDIN_ZEPHYR_TYPES_H
#include <stddef.h>
#include <stdint.h>
#endif
