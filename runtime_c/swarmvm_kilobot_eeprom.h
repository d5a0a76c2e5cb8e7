/*
 * swarmvm on the Kilobot: the EEPROM bytes kilolib keeps for itself.
 *
 * kilolib (kilolib.c, kilo_init) reads the robot's calibration from the ATmega328P's EEPROM:
 * OSCCAL at 0x01, motor calibration 0x05-0x17, IR calibration 0x20-0x6F, TX mask 0x90 and the
 * robot's UID at 0xB0-0xB1; the calibration tools write them. A program that wrote there would
 * change the robot's oscillator, motors, IR and identity at its next start. Anything swarmvm
 * puts in EEPROM (e.g. a table image for svm_load_E) starts at SVM_KILOBOT_EEPROM_FREE or above.
 * No kilolib header is needed: test harnesses that do not link kilolib include this file alone.
 */
#ifndef SWARMVM_KILOBOT_EEPROM_H
#define SWARMVM_KILOBOT_EEPROM_H

#ifdef __cplusplus
extern "C" {
#endif

/* The first EEPROM address kilolib leaves free (its UID ends at 0xB1). */
#define SVM_KILOBOT_EEPROM_FREE 0xB2u

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_KILOBOT_EEPROM_H */
