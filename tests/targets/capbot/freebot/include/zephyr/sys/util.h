/*
 * STAND-IN for the parts of Zephyr's <zephyr/sys/util.h> and <zephyr/sys/util_macro.h> that
 * FreeBot's main.c uses (BIT, ARRAY_SIZE, MIN, IS_ENABLED), with Zephyr's meaning: IS_ENABLED(X)
 * is 1 when X is defined as 1 and 0 when X is undefined, as a C expression. Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_SYS_UTIL_H
#define FREEBOT_STANDIN_SYS_UTIL_H

#define BIT(n) (1UL << (n))
#define ARRAY_SIZE(array) (sizeof(array) / sizeof((array)[0]))
#ifndef MIN
#define MIN(a, b) (((a) < (b)) ? (a) : (b))
#endif
#ifndef MAX
#define MAX(a, b) (((a) > (b)) ? (a) : (b))
#endif

/* Zephyr's technique: a defined-to-1 symbol pastes to Z_IS_ENABLED_1, which expands to "x,",
 * shifting the 1 into the second argument; an undefined one leaves the 0 there. */
#define Z_IS_ENABLED_1 x,
#define IS_ENABLED(config_macro) Z_IS_ENABLED1(config_macro)
#define Z_IS_ENABLED1(config_macro) Z_IS_ENABLED2(Z_IS_ENABLED_##config_macro)
#define Z_IS_ENABLED2(one_or_two_args) Z_IS_ENABLED3(one_or_two_args 1, 0, 0)
#define Z_IS_ENABLED3(ignore_this, val, ...) val

#endif
