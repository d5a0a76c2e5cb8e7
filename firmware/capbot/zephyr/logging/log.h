/*
 * STAND-IN, DECLARATIONS ONLY: Zephyr's logging macros as a generated CapBot main.c uses them,
 * for compile tests without the nRF Connect SDK. Not Zephyr's <zephyr/logging/log.h>.
 */
#ifndef ZEPHYR_STANDIN_LOG_H
#define ZEPHYR_STANDIN_LOG_H

#define LOG_LEVEL_ERR 1
#define LOG_LEVEL_WRN 2
#define LOG_LEVEL_INF 3

void z_log(int level, const char *format, ...);
#define LOG_MODULE_REGISTER(name, level) extern const int z_log_module_##name
#define LOG_ERR(...) z_log(LOG_LEVEL_ERR, __VA_ARGS__)
#define LOG_WRN(...) z_log(LOG_LEVEL_WRN, __VA_ARGS__)
#define LOG_INF(...) z_log(LOG_LEVEL_INF, __VA_ARGS__)

#endif
