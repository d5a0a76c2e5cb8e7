/* swarmvm table image format (docs/image-format.md), for the C runtime (swarmvm.h includes it).
 * Generated from runtime_py/swarmvm_format.py by scripts/format_headers.py: do not edit.
 * After a change of the format run `make format-headers`: tests/compiler/test_format_headers.py
 * fails while this copy differs from what the script writes.
 */
#ifndef SWARMVM_FORMAT_H
#define SWARMVM_FORMAT_H

#define SVM_FORMAT_VERSION 1u
#define SVM_MAGIC 0x494D5653UL          /* "SVMI", as a little-endian u32 */
#define SVM_HEADER_SIZE 16u
#define SVM_CRC_SIZE 2u
#define SVM_MIN_IMAGE_SIZE 18u          /* header and checksum */
#define SVM_MAX_IMAGE_SIZE 65535u       /* the length field is a u16 */
#define SVM_AT_MAGIC 0u                 /* offset of the header's magic */
#define SVM_AT_VERSION 4u               /* offset of the header's version */
#define SVM_AT_FLAGS 5u                 /* offset of the header's flags */
#define SVM_AT_NUM_EVENTS 6u            /* offset of the header's num_events */
#define SVM_AT_NUM_SUPERVISORS 7u       /* offset of the header's num_supervisors */
#define SVM_AT_NUM_STATES 8u            /* offset of the header's num_states */
#define SVM_AT_NUM_TRANSITIONS 10u      /* offset of the header's num_transitions */
#define SVM_AT_STATE_WIDTH 12u          /* offset of the header's state_width */
#define SVM_AT_MASK_BYTES 13u           /* offset of the header's mask_bytes */
#define SVM_AT_LENGTH 14u               /* offset of the header's length */
#define SVM_FLAG_NAMES 1u               /* the names section is present */
#define SVM_FLAG_PROBS 2u               /* the probability section is present */
#define SVM_FLAG_ORDER 4u               /* the order section (source-file event indices) is present */
#define SVM_FLAG_SOURCE 8u              /* the source section (the compatibility layers': skipped) is present */
#define SVM_KNOWN_FLAGS 15u             /* an image with any other flag bit is refused */
#define SVM_FORMAT_MAX_EVENTS 255u      /* the format's limits: a build's SVM_MAX_* stay within them */
#define SVM_FORMAT_MAX_SUPERVISORS 255u
#define SVM_FORMAT_MAX_STATES 65535u
#define SVM_Q15_ONE 32768u              /* probability 1 in the probability section's Q15 */
#define SVM_CRC16_INIT 65535u           /* the checksum's start (CRC-16/MCRF4XX) */
#define SVM_STREAM_CHUNK_DATA 8u        /* image bytes in a stream chunk */

/* Result codes of svm_load and friends (0 = success): swarmvm_format.ErrorCode. */
enum svm_result {
    SVM_OK = 0,
    SVM_ERR_LENGTH = 1,       /* shorter than MIN_IMAGE_SIZE, longer than MAX_IMAGE_SIZE, or L != the length */
    SVM_ERR_MAGIC = 2,        /* not MAGIC */
    SVM_ERR_VERSION = 3,      /* a format version this reader does not read */
    SVM_ERR_CRC = 4,          /* checksum mismatch */
    SVM_ERR_LAYOUT = 5,       /* header inconsistent, sections do not end at L-2, an index or name out of range, or else what the compiler never writes (a name given twice, ...: docs/image-format.md) */
    SVM_ERR_LIMITS = 6,       /* more events/supervisors/states than the build's SVM_MAX_* */
    SVM_ERR_NAMES = 7,        /* swap: a bound event's name is missing from the new image */
    SVM_ERR_EVENT = 8,        /* unknown event index, or a check bound to a controllable event */
    SVM_ERR_NO_BINDINGS = 9,  /* svm_bind without a binding table */
    SVM_ERR_SOURCE = 10       /* an image in memory this build does not read */
};

#endif
