/* A stand-in of kilolib's declarations for the proof (make prove; docs/proof.md): the types,
 * variables and functions runtime_c/swarmvm_kilobot.c uses, declared as kilolib's headers
 * (kilolib.h, message.h, message_crc.h of /work/shared/vendor's kilolib) declare them, and
 * nothing else; no kilolib code. The Kilobot harness (harness_kilobot.c) defines the functions
 * and variables as unknown values, for Eva. */
#ifndef PROOF_KILOLIB_H
#define PROOF_KILOLIB_H

#include <stdint.h>

/* message.h */
typedef enum {
    NORMAL = 0,
    GPS,
    BOOT = 0x80,
    BOOTPGM_PAGE,
    BOOTPGM_SIZE,
    RESET,
    SLEEP,
    WAKEUP,
    CHARGE,
    VOLTAGE,
    RUN,
    READUID,
    CALIB,
} message_type_t;

typedef struct {
    uint8_t data[9];
    uint8_t type;
    uint16_t crc;
} message_t;

/* message_crc.h */
uint16_t message_crc(const message_t *msg);

/* kilolib.h */
typedef struct {
    int16_t low_gain;
    int16_t high_gain;
} distance_measurement_t;

extern volatile uint32_t kilo_ticks;
extern uint16_t kilo_uid;
uint8_t rand_hard(void);
uint8_t rand_soft(void);
void rand_seed(uint8_t seed);

#endif /* PROOF_KILOLIB_H */
