/* How the harnesses load an image of unknown bytes from their buffer: an AVR build that reads
 * images from program memory only (SVM_IMAGE_SOURCES == SVM_FLASH_ONLY, the Kilobot's) loads it
 * with svm_load_P (its svm_load refuses RAM), as its program does; every other build with
 * svm_load. For Eva the buffer is the same memory either way (avr_libc/avr/pgmspace.h). */
#ifndef PROOF_HARNESS_LOAD_H
#define PROOF_HARNESS_LOAD_H
#include "swarmvm.h"
#if defined(__AVR__) && SVM_IMAGE_SOURCES == SVM_FLASH_ONLY
#define proof_load svm_load_P
#else
#define proof_load svm_load
#endif
#endif
