/* STAND-IN for Zephyr's <zephyr/settings/settings.h>: settings_load() (succeeds, loads nothing).
 * Not Zephyr. */
#ifndef FREEBOT_STANDIN_SETTINGS_H
#define FREEBOT_STANDIN_SETTINGS_H
int settings_load(void);
#endif
