/* swarmvm image stream: see swarmvm_stream.h. */
#include "swarmvm_stream.h"

#include "swarmvm.h"

void svm_stream_init(svm_stream_t *stream, uint8_t *buffer, uint16_t capacity)
{
    stream->buffer = buffer;
    stream->capacity = capacity;
    stream->received = 0u;
    stream->length = 0u;
    stream->next = 0u;
    stream->status = SVM_STREAM_IDLE;
    stream->error = 0u;
}

static uint8_t abandon(svm_stream_t *stream, uint8_t status)
{
    stream->received = 0u;
    stream->length = 0u;
    stream->next = 0u;
    stream->status = status;
    return status;
}

uint8_t svm_stream_feed(svm_stream_t *stream, const uint8_t chunk[SVM_CHUNK_BYTES])
{
    uint8_t i;
    if (chunk[0] == 0u) {
        abandon(stream, SVM_STREAM_IDLE);
    } else if ((uint16_t)(chunk[0] + 1u) == stream->next) {
        return stream->status;  /* the last chunk taken, again (senders repeat messages) */
    } else if (stream->status != SVM_STREAM_RECEIVING || chunk[0] != stream->next) {
        return abandon(stream, SVM_STREAM_OUT_OF_SEQUENCE);
    }
    for (i = 0u; i < SVM_CHUNK_DATA; i++) {
        if (stream->length != 0u && stream->received == stream->length) {
            break;  /* padding after the image's last byte */
        }
        if (stream->received >= stream->capacity) {     /* (never past it: >= makes that evident) */
            return abandon(stream, SVM_STREAM_TOO_LARGE);
        }
        stream->buffer[stream->received++] = chunk[1u + i];
        if (stream->received == SVM_AT_LENGTH + 2u) {  /* the header's length field is in */
            stream->length = (uint16_t)(stream->buffer[SVM_AT_LENGTH] | ((uint16_t)stream->buffer[SVM_AT_LENGTH + 1u] << 8));
            if (stream->length > stream->capacity || stream->length < SVM_MIN_IMAGE_SIZE) {
                return abandon(stream, SVM_STREAM_TOO_LARGE);
            }
        }
    }
    stream->next = (uint8_t)(chunk[0] + 1u);
    if (stream->length == 0u || stream->received < stream->length) {
        stream->status = SVM_STREAM_RECEIVING;
        return stream->status;
    }
    stream->error = (uint8_t)svm_validate(stream->buffer, stream->length, 0u);
    stream->status = stream->error == SVM_OK ? SVM_STREAM_COMPLETE : SVM_STREAM_INVALID;
    return stream->status;
}

uint16_t svm_stream_length(const svm_stream_t *stream)
{
    return stream->status == SVM_STREAM_COMPLETE ? stream->length : 0u;
}
