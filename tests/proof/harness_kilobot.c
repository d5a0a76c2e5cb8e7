/* Eva harness over runtime_c/swarmvm_kilobot.c, the Kilobot glue (with swarmvm.c; with
 * swarmvm_stream.c in the STREAM=1 build, the learning files in the LEARNED=1 build; make prove;
 * docs/proof.md).
 *
 * kilolib: tests/proof/kilolib.h's declarations, defined here with unknown values (kilo_ticks,
 * kilo_uid, rand_hard, rand_soft, message_crc). The generated application (svm_kilobot_app_*):
 * the configuration's model's image (proof_image.h, which prove.py writes: what the generated
 * {name}_app.c loads), a dispatch that does what the generated dispatch and checks may do (an
 * action queues its event's message, svm_kilobot_send; a check takes a received message,
 * svm_kilobot_take, or answers an unknown 0 or 1) for any event of the VM; the wire table: every
 * event of the limits public, half sent, half received, each with its own payload (a superset of
 * any model's table). svm_kilobot_begin, with an unknown kilo_uid (and unknown rand_hard bytes),
 * then a loop of an unknown number of iterations (Eva widens it), each doing any of what kilolib's
 * interrupts and loop() do between two of loop()'s calls: a received message of unknown bytes
 * (any type, payload, CRC and distance), the transmit callback and, when it gave a message, its
 * success; svm_kilobot_poll at unknown ticks; svm_kilobot_hold; svm_kilobot_set_options with
 * unknown options and seed; svm_kilobot_step; a reward of any value (LEARNED). With LEARNED the
 * EEPROM is PROOF_EEPROM unknown bytes (any record a run, a power cut or bit rot left), bound by
 * svm_store_avr_eeprom (kilobot_eeprom_stub.h declares it as swarmvm_store.h does on AVR). */
#include "__fc_builtin.h"
#include "swarmvm_kilobot.h"
#include "proof_image.h"

void Frama_C_show_each_reached(void);

volatile uint32_t kilo_ticks;
uint16_t kilo_uid;

uint16_t message_crc(const message_t *msg)
{
    (void)msg;
    return (uint16_t)Frama_C_unsigned_int_interval(0, 0xFFFFu);
}

uint8_t rand_hard(void)
{
    return (uint8_t)Frama_C_interval(0, 255);
}

uint8_t rand_soft(void)
{
    return (uint8_t)Frama_C_interval(0, 255);
}

void rand_seed(uint8_t seed)
{
    (void)seed;
}

#define W(e) {(e), (e) & 1u, {'e', 'v', (char)('0' + (e)), 0, 0, 0, 0, 0, 0}},
const svm_kilobot_wire_t svm_kilobot_wires[] = {
    W(0) W(1) W(2) W(3) W(4) W(5)
#if SVM_MAX_EVENTS > 6
    W(6) W(7) W(8) W(9)
#endif
    {SVM_KILOBOT_END, 0, ""}
};
#if SVM_MAX_EVENTS != 6 && SVM_MAX_EVENTS != 10
#error "the wire table names the events of a model of 6 or 10 events"
#endif

int svm_kilobot_app_load(svm_vm_t *vm)
{
    return svm_load_P(vm, proof_image, sizeof proof_image);
}

uint8_t svm_kilobot_app_dispatch(svm_vm_t *vm, uint8_t event, uint8_t op)
{
    (void)vm;
    if (op == SVM_OP_CHECK) {
        return Frama_C_nondet(0, 1) ? svm_kilobot_take(event) : (uint8_t)Frama_C_interval(0, 1);
    }
    if (Frama_C_nondet(0, 1)) {
        svm_kilobot_send(event);
    }
    return 0;
}

void svm_kilobot_app_on_stream(uint8_t status, uint16_t value)
{
    (void)status;
    (void)value;
}

#if SVM_LEARNED
#ifndef PROOF_EEPROM
#define PROOF_EEPROM 1024u      /* the ATmega328P's EEPROM */
#endif
static uint8_t eeprom[PROOF_EEPROM];

static uint8_t eeprom_read(void *ctx, uint16_t address)
{
    (void)ctx;
    return eeprom[address];
}

static int eeprom_write(void *ctx, uint16_t address, const uint8_t *data, uint16_t length)
{
    uint16_t i;
    (void)ctx;
    for (i = 0; i < length; i++) {
        eeprom[address + i] = data[i];
    }
    return 0;
}

void svm_store_avr_eeprom(svm_store_t *store, uint16_t base, uint16_t slot_size)
{
    store->medium.read = eeprom_read;
    store->medium.write = eeprom_write;
    store->medium.erase = 0;
    store->medium.ctx = 0;
    store->medium.block = 1;
    store->base = base;
    store->slot_size = slot_size;
}
#endif

int main(void)
{
    message_t message;
    distance_measurement_t distance;
    uint32_t seed;
#if SVM_LEARNED
    int32_t reward;
#endif
#if SVM_LEARNED
    Frama_C_make_unknown((char *)eeprom, sizeof eeprom);
#endif
    Frama_C_make_unknown((char *)&kilo_uid, sizeof kilo_uid);     /* int may be 16 bits */
    Frama_C_make_unknown((char *)&kilo_ticks, sizeof kilo_ticks);
    svm_kilobot_hold((uint8_t)Frama_C_interval(0, 1));
    (void)svm_kilobot_begin();
    while (Frama_C_nondet(0, 1)) {
        Frama_C_show_each_reached();            /* prove.py: the loop was analysed */
        if (Frama_C_nondet(0, 1)) {             /* kilolib's IR interrupt */
            Frama_C_make_unknown((char *)&message, sizeof message);
            Frama_C_make_unknown((char *)&distance, sizeof distance);
            (void)svm_kilobot_receive(&message, &distance);
        }
        if (Frama_C_nondet(0, 1) && svm_kilobot_transmit() != 0 && Frama_C_nondet(0, 1)) {
            svm_kilobot_transmitted();          /* kilolib's Timer0 interrupt: sent */
        }
        Frama_C_make_unknown((char *)&kilo_ticks, sizeof kilo_ticks);   /* any ticks passed */
        svm_kilobot_poll();
        if (Frama_C_nondet(0, 1)) {
            svm_kilobot_hold((uint8_t)Frama_C_interval(0, 255));
        }
        if (Frama_C_nondet(0, 1)) {
            Frama_C_make_unknown((char *)&seed, sizeof seed);
            svm_kilobot_set_options((uint8_t)Frama_C_interval(0, 255), seed);
        }
        if (Frama_C_nondet(0, 1)) {
            (void)svm_kilobot_step();
        }
#if SVM_LEARNED
        Frama_C_make_unknown((char *)&reward, sizeof reward);
        svm_kilobot_reward(reward);
#endif
    }
    return 0;
}
