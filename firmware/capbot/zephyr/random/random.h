/*
 * STAND-IN, DECLARATIONS ONLY: Zephyr's sys_rand32_get() for compile tests without the nRF
 * Connect SDK. Not Zephyr's <zephyr/random/random.h>.
 */
#ifndef ZEPHYR_STANDIN_RANDOM_H
#define ZEPHYR_STANDIN_RANDOM_H

#include <stdint.h>

uint32_t sys_rand32_get(void);

#endif
