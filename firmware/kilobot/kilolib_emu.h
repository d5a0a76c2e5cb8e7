/* Emulator-only additions to kilolib, written for the swarmvm project: NOT part of kilolib
 * (firmware/kilobot/kilolib_emu.c implements them in simavr). Test and demo programs use them
 * to print on USART0, to act after each loop() and to receive scripted messages.
 */
#ifndef KILOLIB_EMU_H
#define KILOLIB_EMU_H

#include <stdint.h>

/* Called after each loop(), before the outgoing message is reported. kilolib_emu.c defines
 * it weak and empty; a test program may define its own (e.g. to print a trace line). */
void kilo_emu_after_loop(void);

void kilo_emu_put(char c);
void kilo_emu_print(const char *text);
void kilo_emu_print_uint(uint16_t value);

/* Scripted incoming messages. Build kilolib_emu.c with -DKILO_EMU_SCRIPT and a header
 * "kilo_emu_script.h" on the include path defining KILO_EMU_SCRIPT_COUNT and
 *     static const kilo_emu_rx_t kilo_emu_script[KILO_EMU_SCRIPT_COUNT] PROGMEM = { ... };
 * sorted by `loop`: before loop() number `loop` (counted from 0) runs, each such message is
 * handed to kilo_message_rx as the IR receiver would, with its CRC and a zero distance. The
 * header may also set KILO_EMU_LOOPS. */
typedef struct {
    uint16_t loop;
    uint8_t type;
    uint8_t data[9];
} kilo_emu_rx_t;

#endif /* KILOLIB_EMU_H */
