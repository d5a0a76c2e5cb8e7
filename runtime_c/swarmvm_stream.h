/*
 * swarmvm image stream: reassemble a table image sent as small messages, so a running robot
 * can be given new control logic over its message channel (the Kilobot's 9-byte payloads).
 *
 * A chunk is 9 bytes: a sequence number, then 8 bytes of the image (chunk k carries image
 * bytes 8k .. 8k+7; the last chunk is padded). The image's own header gives its length and
 * its last two bytes are its CRC-16, so the stream needs no other framing: when the bytes up
 * to that length have arrived, the whole image is checked with svm_validate, and only a valid
 * image is offered to the application, which swaps it in between two steps with svm_load.
 * Chunk 0 always (re)starts a reception; a chunk out of sequence abandons the current one,
 * except the last chunk taken arriving again (a Kilobot repeats a message until it changes
 * it), which changes nothing. Take a COMPLETE image before feeding the next chunk.
 * The buffer must not hold the image the VM is running: give the stream a buffer of its own.
 */
#ifndef SWARMVM_STREAM_H
#define SWARMVM_STREAM_H

#include <stdint.h>

#include "swarmvm_format.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A chunk: its sequence byte, then SVM_STREAM_CHUNK_DATA bytes of the image (swarmvm_format.h). */
#define SVM_CHUNK_DATA SVM_STREAM_CHUNK_DATA
#define SVM_CHUNK_BYTES (1u + SVM_CHUNK_DATA)

enum svm_stream_status {
    SVM_STREAM_IDLE = 0,        /* waiting for chunk 0 */
    SVM_STREAM_RECEIVING = 1,   /* chunk accepted, more to come */
    SVM_STREAM_COMPLETE = 2,    /* a whole, valid image is in the buffer */
    SVM_STREAM_OUT_OF_SEQUENCE = 3, /* chunk ignored; reception abandoned until the next chunk 0 */
    SVM_STREAM_TOO_LARGE = 4,   /* the image's length exceeds the buffer; abandoned */
    SVM_STREAM_INVALID = 5      /* complete but refused by svm_validate (see svm_stream_error) */
};

typedef struct svm_stream {
    uint8_t *buffer;
    uint16_t capacity;
    uint16_t received;   /* bytes stored so far */
    uint16_t length;     /* the image's length, once its header has arrived; else 0 */
    uint8_t next;        /* sequence number expected next */
    uint8_t status;      /* last enum svm_stream_status */
    uint8_t error;       /* svm_validate's result code when status is SVM_STREAM_INVALID */
} svm_stream_t;

void svm_stream_init(svm_stream_t *stream, uint8_t *buffer, uint16_t capacity);

/* Take one 9-byte chunk; returns the new status. */
uint8_t svm_stream_feed(svm_stream_t *stream, const uint8_t chunk[SVM_CHUNK_BYTES]);

/* The image's length once COMPLETE (0 otherwise). */
uint16_t svm_stream_length(const svm_stream_t *stream);

#ifdef __cplusplus
}
#endif

#endif
