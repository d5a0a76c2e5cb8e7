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
 * store is the AVR build's own (swarmvm_store.c's svm_store_avr_eeprom over avr-libc's EEPROM
 * calls), whose reads answer any byte at any address (avr_libc/avr/eeprom.h: any record a run, a
 * power cut or bit rot left). */
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
/* The EEPROM behind avr_libc/avr/eeprom.h's contracts: any bytes at any address. */
volatile uint8_t proof_eeprom_cells;
#endif

int main(void)
{
    message_t message;
    distance_measurement_t distance;
    uint32_t seed;
#if SVM_LEARNED
    int32_t reward;
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
