/*
 * A Kilobot on simavr's ATmega328P model: the infrared channel, the one part of the robot that
 * simavr cannot model. Written for the swarmvm project (host program, links libsimavr).
 *
 * Everything on the chip is simavr's model (CPU at 8 MHz, Timer0 and its compare interrupt that
 * advances kilo_ticks and sends messages, Timer1, analog comparator, ports, USART0, EEPROM) and
 * every instruction run is the image's: the real kilolib and the application. This board adds
 * only what lies outside the chip, and nothing else:
 *   - IR light in: a scheduled message becomes the light pulses kilolib's receiver decodes,
 *     rising edges of the analog comparator (AIN0 driven above AIN1) at kilolib's bit timing
 *     (269 cycles a bit; a leading byte 0, then the 12 bytes of message_t, each as start bit,
 *     8 data bits, stop bit). The overhead controller's RUN message, which starts a program on
 *     a real Kilobot, is sent this way too (type 0x88: the schedule's first line).
 *   - IR light out: kilolib's transmitter (message_send) flashes the IR LED on PORTB (tx_mask);
 *     the board decodes those pulses with the same timing and prints each message it sees.
 *   - one medium: a scheduled message waits while the robot transmits, and one cut short by the
 *     robot's own transmission (a collision) is sent again, whole, once the channel is free.
 *   - USART0 output (kilolib's debug.h) printed line by line; EEPROM contents given and dumped;
 *     the RGB LED's colour (kilolib's set_color drives it through DDRC/DDRD) reported on change.
 * The distance (ADC) of a received message is whatever simavr's ADC reads: not modelled.
 *
 * usage: kilobot_board [-t TICKS_ADDR] [-n TICKS] [-c CYCLES] [-m SCHEDULE] [-e EEPROM_IN]
 *                      [-E EEPROM_OUT] [-r ADDR] [-s ADDR] [-p STEP_PC [-k CHECK_PC]... [-x SCRIPT]] IMAGE.elf
 *   -t  SRAM address of kilo_ticks (avr-nm): schedule times and -n are in kilolib ticks
 *   -n  stop once kilo_ticks reaches this;  -c  stop after this many cycles (default 4e9)
 *   -m  schedule file, one message a line: "TICK TYPE DATA" (TYPE hex, DATA 18 hex digits),
 *       sent once kilo_ticks >= TICK and the channel is free, in file order
 *   -e  raw EEPROM contents from address 0;  -E  the EEPROM (1,024 bytes) written there at the end
 *   -r  SRAM address of a 4-byte variable printed at the end ("#ram ADDR VALUE", little-endian)
 *   -s  stack painting: SRAM from this address (the end of .bss) to RAMEND is filled with 0xA5
 *       before the run; at the end "#stack LOWEST" is the lowest address no longer holding it
 *       (RAMEND + 1 when none: the stack's high-water mark is RAMEND + 1 - LOWEST bytes)
 *   -p  cycles per step: the flash byte address of svm_step; each call prints "#step N CYCLES",
 *       the cycles from its first instruction to its return (interrupts taken meanwhile included)
 *   -k  with -x: the address of a function svm_step calls through its dispatch pointer
 *       (repeatable): while a step runs, a check (op SVM_OP_CHECK in r20) entered there returns
 *       the script's bit for its event (r22) instead of the program's answer, set in r24 when it
 *       returns (the outermost of nested ones)
 *   -x  event script: one line per step, that step's event mask as hex bytes (event e = bit
 *       e % 8 of byte e / 8); the run stops ("steps") once the step after the last line began,
 *       so the last line's step is measured whole
 * Output (stdout), in order of time: the image's USART0 lines as they are; "#rx TICK TYPE DATA"
 * once a scheduled message was sent; "#tx TICK TYPE DATA ok|badcrc" for each message the robot
 * sent; "#collision TICK"; "#led TICK RGB" (set_color's value) on each change; "#step N CYCLES"
 * (-p); last "#end TICK CYCLES done|crashed|ticks|cycles|steps".
 */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "avr_acomp.h"
#include "avr_eeprom.h"
#include "avr_ioport.h"
#include "avr_uart.h"
#include "sim_avr.h"
#include "sim_cycle_timers.h"
#include "sim_elf.h"
#include "sim_io.h"
#include "sim_irq.h"

#define BIT_CYCLES 269u                 /* kilolib's rx_bitcycles */
#define MESSAGE_BYTES 12u               /* sizeof(message_t): data[9], type, crc */
#define MAX_PULSES (2u + MESSAGE_BYTES * 10u)
#define PULSE_CYCLES 8u                 /* how long the light stays on */
#define LIGHT_MV 2000u                  /* AIN0 while lit (AIN1 stays at 0 V) */
#define POLL_CYCLES 512u
/* Quiet time between two messages sent to the robot: kilolib handles a whole message (CRC,
 * the program's callback) in its receive interrupt, after the last stop bit. */
#define GAP_CYCLES (11u * BIT_CYCLES)
#define TX_LED_BITS 0xC7u               /* PORTB bits kilolib's tx_mask may use */
#define EEPROM_BYTES 1024u
#define MAX_SCHEDULE 4096u

typedef struct {
    uint32_t tick;
    uint8_t raw[MESSAGE_BYTES];
} scheduled_t;

static avr_t *avr;
static avr_irq_t *ain0;
static long ticks_at = -1, read_at = -1, paint_from = -1;
#define STACK_PAINT 0xA5u                /* -s: the pattern the stack is painted with */
static uint32_t stop_tick;
static int has_stop_tick;
static avr_cycle_count_t stop_cycle = 4000000000ull;

/* -p / -k / -x: cycles per step, checks answered from an event script. */
#define MAX_CHECK_PCS 8u
#define MAX_MASK_BYTES 32u
#define MAX_SCRIPT_STEPS 100000u
#define OP_CHECK 0u                     /* swarmvm.h: SVM_OP_CHECK */
#define NO_FRAME 0x10000L               /* no call being watched */
static long step_pc = -1;
static long check_pcs[MAX_CHECK_PCS];
static unsigned num_check_pcs;
static uint8_t (*script)[MAX_MASK_BYTES];
static unsigned script_steps, steps_begun;
static int has_script;
static long step_sp = NO_FRAME, check_sp = NO_FRAME;
static uint8_t check_event;
static avr_cycle_count_t step_start;
static const char *stop_reason;

static scheduled_t schedule[MAX_SCHEDULE];
static unsigned num_scheduled, next_scheduled;

/* The message being sent to the robot: pulse times relative to its first pulse. */
static uint32_t pulses[MAX_PULSES];
static unsigned num_pulses, next_pulse, sending;
static avr_cycle_count_t train_start, train_end;

/* Decoder of the robot's IR pulses (kilolib's receiver, same arithmetic). */
static struct {
    int leading_bit, leading_byte;
    unsigned index;
    uint8_t value;
    avr_cycle_count_t start, last;
    uint8_t raw[MESSAGE_BYTES];
} tx = {1, 1, 0, 0, 0, 0, {0}};
static uint8_t led;

static char line[512];
static unsigned line_length;

static uint32_t ticks(void)
{
    uint32_t t = 0;
    int i;
    if (ticks_at < 0) {
        return 0;
    }
    for (i = 3; i >= 0; i--) {
        t = (t << 8) | avr->data[ticks_at + i];
    }
    return t;
}

static uint16_t crc_ccitt_update(uint16_t crc, uint8_t data)
{
    data ^= (uint8_t)(crc & 0xffu);
    data ^= (uint8_t)(data << 4);
    return (uint16_t)((((uint16_t)data << 8) | (crc >> 8)) ^ (uint8_t)(data >> 4) ^ ((uint16_t)data << 3));
}

/* kilolib's message_crc over data[9] and type. */
static uint16_t message_crc(const uint8_t *raw)
{
    uint16_t crc = 0xffffu;
    unsigned i;
    for (i = 0; i < MESSAGE_BYTES - 2u; i++) {
        crc = crc_ccitt_update(crc, raw[i]);
    }
    return crc;
}

static void print_message(const char *tag, const uint8_t *raw, const char *suffix)
{
    unsigned i;
    printf("#%s %u %02x ", tag, (unsigned)ticks(), raw[9]);
    for (i = 0; i < 9u; i++) {
        printf("%02x", raw[i]);
    }
    printf("%s\n", suffix);
}

/* ---- light in: a message as comparator edges ---- */

static void encode(const uint8_t *raw)
{
    unsigned byte, bit;
    uint32_t start = 10u * BIT_CYCLES;
    num_pulses = 0;
    pulses[num_pulses++] = 0;                       /* leading byte (value 0): start ... */
    pulses[num_pulses++] = 9u * BIT_CYCLES;         /* ... and stop bit */
    for (byte = 0; byte < MESSAGE_BYTES; byte++, start += 10u * BIT_CYCLES) {
        pulses[num_pulses++] = start;
        for (bit = 0; bit < 8u; bit++) {
            if (raw[byte] & (1u << bit)) {
                pulses[num_pulses++] = start + (bit + 1u) * BIT_CYCLES;
            }
        }
        pulses[num_pulses++] = start + 9u * BIT_CYCLES;
    }
}

static avr_cycle_count_t light_off(avr_t *a, avr_cycle_count_t when, void *param);

static avr_cycle_count_t light_on(avr_t *a, avr_cycle_count_t when, void *param)
{
    (void)when;
    (void)param;
    avr_raise_irq(ain0, LIGHT_MV);
    avr_cycle_timer_register(a, PULSE_CYCLES, light_off, NULL);
    return 0;
}

static avr_cycle_count_t light_off(avr_t *a, avr_cycle_count_t when, void *param)
{
    (void)when;
    (void)param;
    avr_raise_irq(ain0, 0);
    if (++next_pulse < num_pulses) {
        avr_cycle_timer_register(a, train_start + pulses[next_pulse] - a->cycle, light_on, NULL);
    } else {
        sending = 0;
        train_end = a->cycle;
        print_message("rx", schedule[next_scheduled].raw, "");
        next_scheduled++;
    }
    return 0;
}

static void abort_train(void)
{
    avr_cycle_timer_cancel(avr, light_on, NULL);
    avr_cycle_timer_cancel(avr, light_off, NULL);
    avr_raise_irq(ain0, 0);
    sending = 0;
    printf("#collision %u\n", (unsigned)ticks());
}

/* The robot lit its LED lately. After its last pulse the channel counts as busy for 24 bits:
 * a transmission the robot cut short (collision) leaves kilolib's receiver waiting for its own
 * timeout (11 bits, counted from when its interrupt could run, after the send), and a message
 * sent into that wait would be framed wrongly and lost. */
static int robot_transmitting(void)
{
    return tx.last != 0 && avr->cycle - tx.last < 24u * BIT_CYCLES;
}

/* ---- light out: the robot's IR LED ---- */

static void decoder_reset(void)
{
    tx.leading_bit = 1;
    tx.leading_byte = 1;
    tx.index = 0;
}

static void led_pulse(avr_cycle_count_t now)
{
    uint32_t dt;
    if (sending) {
        abort_train();
    }
    if ((!tx.leading_bit || !tx.leading_byte) && now - tx.last >= 11u * BIT_CYCLES) {
        decoder_reset();                            /* kilolib's receive timeout */
    }
    tx.last = now;
    if (tx.leading_bit) {
        tx.start = now;
        tx.value = 0;
        tx.leading_bit = 0;
        return;
    }
    dt = (uint32_t)(now - tx.start);
    if (dt <= BIT_CYCLES / 2u || dt >= BIT_CYCLES * 9u + BIT_CYCLES / 2u) {
        decoder_reset();                            /* a stray pulse */
        return;
    }
    if ((dt - BIT_CYCLES / 2u) / BIT_CYCLES <= 7u) {
        tx.value |= (uint8_t)(1u << ((dt - BIT_CYCLES / 2u) / BIT_CYCLES));
        return;
    }
    tx.leading_bit = 1;                             /* stop bit */
    if (tx.leading_byte) {
        if (tx.value == 0) {
            tx.leading_byte = 0;
            tx.index = 0;
        }
        return;
    }
    tx.raw[tx.index++] = tx.value;
    if (tx.index == MESSAGE_BYTES) {
        uint16_t crc = (uint16_t)(tx.raw[10] | (tx.raw[11] << 8));
        print_message("tx", tx.raw, crc == message_crc(tx.raw) ? " ok" : " badcrc");
        decoder_reset();
    }
}

static void on_port_b(avr_irq_t *irq, uint32_t value, void *param)
{
    uint8_t lit = (uint8_t)(value & TX_LED_BITS);
    (void)irq;
    (void)param;
    if (lit & (uint8_t)~led) {
        led_pulse(avr->cycle);
    }
    led = lit;
}

/* ---- the LED: set_color's bits 0-5 are DDRD5, DDRD4, DDRC3, DDRC2, DDRC5, DDRC4, read at
 * each poll (a 1 ms blink lasts 8,000 cycles) ---- */

#define DDRC_AT 0x27u
#define DDRD_AT 0x2Au

static uint8_t colour;

static void watch_led(void)
{
    uint8_t c = avr->data[DDRC_AT], d = avr->data[DDRD_AT];
    uint8_t now = (uint8_t)(((d >> 5) & 1u) | (((d >> 4) & 1u) << 1) | (((c >> 3) & 1u) << 2) |
                            (((c >> 2) & 1u) << 3) | (((c >> 5) & 1u) << 4) | (((c >> 4) & 1u) << 5));
    if (now != colour) {
        colour = now;
        printf("#led %u %u\n", (unsigned)ticks(), (unsigned)colour);
    }
}

/* ---- USART0 ---- */

static void on_uart(avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    (void)param;
    if (value == '\n' || line_length == sizeof line - 1u) {
        line[line_length] = '\0';
        printf("%s\n", line);
        line_length = 0;
    }
    if (value != '\n') {
        line[line_length++] = (char)value;
    }
}

/* ---- the schedule and the end ---- */

static avr_cycle_count_t poll(avr_t *a, avr_cycle_count_t when, void *param)
{
    uint32_t now = ticks();
    (void)param;
    watch_led();
    if (has_stop_tick && now >= stop_tick) {
        stop_reason = "ticks";
    } else if (a->cycle >= stop_cycle) {
        stop_reason = "cycles";
    }
    if (!sending && next_scheduled < num_scheduled && now >= schedule[next_scheduled].tick &&
        !robot_transmitting() && (train_end == 0 || a->cycle - train_end >= GAP_CYCLES)) {
        encode(schedule[next_scheduled].raw);
        sending = 1;
        next_pulse = 0;
        train_start = a->cycle + 1u;
        avr_cycle_timer_register(a, 1, light_on, NULL);
    }
    return when + POLL_CYCLES;
}

static int hex_bytes(const char *text, uint8_t *out, unsigned count)
{
    unsigned i;
    for (i = 0; i < count; i++) {
        unsigned v;
        if (sscanf(text + 2u * i, "%2x", &v) != 1) {
            return -1;
        }
        out[i] = (uint8_t)v;
    }
    return text[2u * count] == '\0' || text[2u * count] == '\n' ? 0 : -1;
}

static void read_schedule(const char *path)
{
    char text[256];
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        perror(path);
        exit(2);
    }
    while (fgets(text, sizeof text, f) != NULL) {
        unsigned long tick;
        unsigned type;
        char data[64];
        scheduled_t *s = &schedule[num_scheduled];
        uint16_t crc;
        if (text[0] == '\n' || text[0] == '#') {
            continue;
        }
        if (num_scheduled == MAX_SCHEDULE || sscanf(text, "%lu %x %63s", &tick, &type, data) != 3 ||
            hex_bytes(data, s->raw, 9u) != 0) {
            fprintf(stderr, "%s: bad line: %s", path, text);
            exit(2);
        }
        s->tick = (uint32_t)tick;
        s->raw[9] = (uint8_t)type;
        crc = message_crc(s->raw);
        s->raw[10] = (uint8_t)(crc & 0xffu);
        s->raw[11] = (uint8_t)(crc >> 8);
        num_scheduled++;
    }
    fclose(f);
}

/* -x: one line per step of hex mask bytes ('#' lines and blank lines skipped). */
static void read_script(const char *path)
{
    char text[2u * MAX_MASK_BYTES + 8u];
    FILE *f = fopen(path, "r");
    has_script = 1;
    if (f == NULL) {
        perror(path);
        exit(2);
    }
    script = calloc(MAX_SCRIPT_STEPS, sizeof *script);
    if (script == NULL) {
        exit(2);
    }
    while (fgets(text, sizeof text, f) != NULL) {
        size_t length = strcspn(text, "\n");
        if (length == 0u || text[0] == '#') {
            continue;
        }
        if (script_steps == MAX_SCRIPT_STEPS || length % 2u != 0u || length > 2u * MAX_MASK_BYTES ||
            hex_bytes(text, script[script_steps], (unsigned)(length / 2u)) != 0) {
            fprintf(stderr, "%s: bad line: %s", path, text);
            exit(2);
        }
        script_steps++;
    }
    fclose(f);
}

static long stack_pointer(void)
{
    return (long)avr->data[R_SPL] | (long)avr->data[R_SPH] << 8;
}

static int is_check_pc(long pc)
{
    unsigned i;
    for (i = 0; i < num_check_pcs; i++) {
        if (check_pcs[i] == pc) {
            return 1;
        }
    }
    return 0;
}

/* Before each instruction: a call of svm_step begins (its cycles are counted from here), a
 * watched dispatch is entered for a check, or one of them has returned (the stack pointer is
 * back above the return address its call pushed: 2 bytes on the ATmega328P). */
static void watch_step(void)
{
    long pc = (long)avr->pc, sp = stack_pointer();
    if (step_sp == NO_FRAME) {
        if (pc == step_pc) {
            if (has_script && steps_begun == script_steps) {
                stop_reason = "steps";
                return;
            }
            step_sp = sp;
            step_start = avr->cycle;
            steps_begun++;
        }
        return;
    }
    if (check_sp == NO_FRAME) {
        if (has_script && is_check_pc(pc) && avr->data[20] == OP_CHECK) {
            check_sp = sp;
            check_event = avr->data[22];
        }
    } else if (sp >= check_sp + 2) {
        const uint8_t *row = script[steps_begun - 1u];
        avr->data[24] = (uint8_t)((row[check_event / 8u] >> (check_event % 8u)) & 1u);
        check_sp = NO_FRAME;
    }
    if (sp >= step_sp + 2) {
        printf("#step %u %llu\n", steps_begun, (unsigned long long)(avr->cycle - step_start));
        step_sp = NO_FRAME;
    }
}

static void eeprom_io(const char *path, int save)
{
    uint8_t bytes[EEPROM_BYTES];
    avr_eeprom_desc_t desc;
    FILE *f = fopen(path, save ? "wb" : "rb");
    if (f == NULL) {
        perror(path);
        exit(2);
    }
    memset(bytes, 0xff, sizeof bytes);
    desc.ee = bytes;
    desc.offset = 0;
    desc.size = save ? EEPROM_BYTES : (uint32_t)fread(bytes, 1, EEPROM_BYTES, f);
    if (save) {
        avr_ioctl(avr, AVR_IOCTL_EEPROM_GET, &desc);
        fwrite(desc.ee, 1, EEPROM_BYTES, f);
    } else {
        avr_ioctl(avr, AVR_IOCTL_EEPROM_SET, &desc);
    }
    fclose(f);
}

/* simavr's own messages ("Loaded ... .text") would mix with the robot's output: errors only. */
static void log_errors(avr_t *a, const int level, const char *format, va_list ap)
{
    (void)a;
    if (level <= LOG_ERROR) {
        vfprintf(stderr, format, ap);
    }
}

int main(int argc, char **argv)
{
    elf_firmware_t firmware;
    const char *schedule_path = NULL, *eeprom_in = NULL, *eeprom_out = NULL;
    uint32_t flags = 0;
    int option, state = cpu_Running;
    while ((option = getopt(argc, argv, "t:n:c:m:e:E:r:s:p:k:x:")) != -1) {
        switch (option) {
        case 't': ticks_at = strtol(optarg, NULL, 0); break;
        case 'n': stop_tick = (uint32_t)strtoul(optarg, NULL, 0); has_stop_tick = 1; break;
        case 'c': stop_cycle = strtoull(optarg, NULL, 0); break;
        case 'm': schedule_path = optarg; break;
        case 'e': eeprom_in = optarg; break;
        case 'E': eeprom_out = optarg; break;
        case 'r': read_at = strtol(optarg, NULL, 0); break;
        case 's': paint_from = strtol(optarg, NULL, 0); break;
        case 'p': step_pc = strtol(optarg, NULL, 0); break;
        case 'k':
            if (num_check_pcs == MAX_CHECK_PCS) {
                return 2;
            }
            check_pcs[num_check_pcs++] = strtol(optarg, NULL, 0);
            break;
        case 'x': read_script(optarg); break;
        default: return 2;
        }
    }
    if (optind != argc - 1 || (has_stop_tick && ticks_at < 0) || ((has_script || num_check_pcs) && step_pc < 0)) {
        fprintf(stderr, "usage: kilobot_board [-t TICKS_ADDR] [-n TICKS] [-c CYCLES] [-m SCHEDULE] "
                        "[-e EEPROM_IN] [-E EEPROM_OUT] [-r ADDR] [-s ADDR] [-p STEP_PC [-k CHECK_PC]... "
                        "[-x SCRIPT]] IMAGE.elf\n");
        return 2;
    }
    avr_global_logger_set(log_errors);
    memset(&firmware, 0, sizeof firmware);
    if (elf_read_firmware(argv[optind], &firmware) != 0) {
        fprintf(stderr, "kilobot_board: cannot read %s\n", argv[optind]);
        return 2;
    }
    avr = avr_make_mcu_by_name("atmega328p");
    if (avr == NULL) {
        return 2;
    }
    avr_init(avr);
    avr->frequency = 8000000;
    avr->log = 0;
    avr_load_firmware(avr, &firmware);
    if (schedule_path != NULL) {
        read_schedule(schedule_path);
    }
    if (eeprom_in != NULL) {
        eeprom_io(eeprom_in, 0);
    }
    if (paint_from > 0 && paint_from <= avr->ramend) {
        memset(avr->data + paint_from, STACK_PAINT, (size_t)(avr->ramend + 1 - paint_from));
    }
    avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
    flags &= ~(uint32_t)AVR_UART_FLAG_STDIO;
    avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), on_uart, NULL);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), IOPORT_IRQ_REG_PORT), on_port_b, NULL);
    ain0 = avr_io_getirq(avr, AVR_IOCTL_ACOMP_GETIRQ, ACOMP_IRQ_AIN0);
    if (ain0 == NULL) {
        fprintf(stderr, "kilobot_board: this simavr has no analog comparator model\n");
        return 2;
    }
    avr_raise_irq(avr_io_getirq(avr, AVR_IOCTL_ACOMP_GETIRQ, ACOMP_IRQ_AIN1), 0);
    avr_raise_irq(ain0, 0);
    avr_cycle_timer_register(avr, POLL_CYCLES, poll, NULL);
    while (stop_reason == NULL && state != cpu_Done && state != cpu_Crashed) {
        if (step_pc >= 0) {
            watch_step();
            if (stop_reason != NULL) {
                break;
            }
        }
        state = avr_run(avr);
    }
    if (line_length != 0) {
        line[line_length] = '\0';
        printf("%s\n", line);
    }
    if (eeprom_out != NULL) {
        eeprom_io(eeprom_out, 1);
    }
    if (read_at >= 0) {
        printf("#ram %ld %lu\n", read_at, (unsigned long)avr->data[read_at] | (unsigned long)avr->data[read_at + 1] << 8 |
               (unsigned long)avr->data[read_at + 2] << 16 | (unsigned long)avr->data[read_at + 3] << 24);
    }
    if (paint_from > 0 && paint_from <= avr->ramend) {
        long lowest = paint_from;
        while (lowest <= avr->ramend && avr->data[lowest] == STACK_PAINT) {
            lowest++;
        }
        printf("#stack %ld\n", lowest);
    }
    printf("#end %u %llu %s\n", (unsigned)ticks(), (unsigned long long)avr->cycle,
           stop_reason != NULL ? stop_reason : state == cpu_Done ? "done" : "crashed");
    return state == cpu_Crashed ? 1 : 0;
}
