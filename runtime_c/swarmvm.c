/*
 * swarmvm C VM core (see swarmvm.h). The tables are read in place from the image; a
 * transition is found with the state's `defined` mask and a popcount (docs/image-format.md),
 * so a step costs a few mask operations per supervisor whatever the automata's size.
 */
#include "swarmvm.h"

#define Q15_ONE 32768u
#define SEED_FOR_ZERO 0x9E3779B9UL

/* Inlining hint for the step's helpers (C99 `inline` on a static function). */
#define SVM_INLINE inline

/* ---- image access ------------------------------------------------------------------------
 * An image is read where it lives: `source` is SVM_SOURCE_RAM, _FLASH or _EEPROM. On AVR the
 * build chooses which sources it reads (SVM_IMAGE_SOURCES): SVM_FLASH_ONLY reads every byte
 * with pgm_read_byte and no branch, SVM_RAM_ONLY with plain loads, SVM_FLASH_OR_RAM (default)
 * tests the source per read, SVM_ANY_SOURCE also reads EEPROM. Elsewhere all are plain loads. */
#if defined(__AVR__) && SVM_IMAGE_SOURCES == SVM_FLASH_ONLY
#define READ(image, source, at) ((void)(source), SVM_FLASH_BYTE((image) + (at)))
#elif defined(__AVR__) && SVM_IMAGE_SOURCES == SVM_FLASH_OR_RAM
#define READ(image, source, at) ((source) != SVM_SOURCE_RAM ? SVM_FLASH_BYTE((image) + (at)) : (image)[at])
#elif defined(__AVR__) && SVM_IMAGE_SOURCES == SVM_ANY_SOURCE
#include <avr/eeprom.h>
#define READ(image, source, at) ((source) == SVM_SOURCE_FLASH ? SVM_FLASH_BYTE((image) + (at)) : \
                                 (source) == SVM_SOURCE_EEPROM ? eeprom_read_byte((image) + (at)) : (image)[at])
#else
#define READ(image, source, at) ((void)(source), (image)[at])
#endif

static uint8_t rd_raw(const uint8_t *image, uint8_t source, uint16_t at)
{
    return (uint8_t)READ(image, source, at);
}

static uint16_t rd16_raw(const uint8_t *image, uint8_t source, uint16_t at)
{
    return (uint16_t)(rd_raw(image, source, at) | ((uint16_t)rd_raw(image, source, (uint16_t)(at + 1u)) << 8));
}

#define RD(vm, at) rd_raw((vm)->image, (vm)->source, (uint16_t)(at))
#define RD16(vm, at) rd16_raw((vm)->image, (vm)->source, (uint16_t)(at))

/* Whether an image read from `source` is in AVR program memory, where pgm_read_word/dword
 * read 2 or 4 bytes at once. */
#if defined(__AVR__) && SVM_IMAGE_SOURCES == SVM_FLASH_ONLY
#define IN_FLASH(source) ((void)(source), 1)
#elif defined(__AVR__) && SVM_IMAGE_SOURCES != SVM_RAM_ONLY
#define IN_FLASH(source) ((source) == SVM_SOURCE_FLASH)
#else
#define IN_FLASH(source) ((void)(source), 0)
#endif

/* The same through a pointer into the image, for the step's loops (no base + offset sums). */
#define PEEK(source, p) READ((p), (source), 0)
static SVM_INLINE uint16_t peek16(uint8_t source, const uint8_t *p)
{
#if defined(__AVR__) && SVM_IMAGE_SOURCES != SVM_RAM_ONLY
    if (IN_FLASH(source)) {
        return pgm_read_word(p);
    }
#endif
    return (uint16_t)(PEEK(source, p) | ((uint16_t)PEEK(source, p + 1) << 8));
}

/* Section layout, from the header fields (docs/image-format.md). */
#define CONTROLLABLE_AT SVM_HEADER_SIZE
#define PUBLIC_AT(m) (SVM_HEADER_SIZE + (uint16_t)(m))
#define SUPS_AT(m) (SVM_HEADER_SIZE + 2u * (uint16_t)(m))
#define SUP_SIZE(m) ((uint16_t)(m) + 6u)
#define STATE_SIZE(m) ((uint16_t)(m) + 2u)
#define SUP_AT(vm, s) (SUPS_AT((vm)->mask_bytes) + (uint16_t)(s) * SUP_SIZE((vm)->mask_bytes))
/* vm->state[s] is the supervisor's *global* state number: its record is at
 * states_at + state * STATE_SIZE(m), found without reading the supervisor's first state. */

/* A loaded image's mask width, clamped to 1..SVM_MASK_BYTES for the compiler's sake (load has
 * checked it already), so that loops over it provably stay inside the VM's mask arrays. */
#define MASK_WIDTH(m) ((uint8_t)((m) - 1u) < SVM_MASK_BYTES ? (uint8_t)(m) : (uint8_t)1u)

/* Set bits of a byte. AVR shifts one bit per instruction, so there a table in flash (256 B,
 * SVM_POPCOUNT_TABLE) does it in one lpm: about 4 % off a step; elsewhere bit arithmetic. */
#if SVM_POPCOUNT_TABLE
static const uint8_t ones_in[256] SVM_PROGMEM = {
    0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 1, 2, 2, 3, 2, 3, 3, 4, 2, 3, 3, 4, 3, 4, 4, 5,
    1, 2, 2, 3, 2, 3, 3, 4, 2, 3, 3, 4, 3, 4, 4, 5, 2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6,
    1, 2, 2, 3, 2, 3, 3, 4, 2, 3, 3, 4, 3, 4, 4, 5, 2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6,
    2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6, 3, 4, 4, 5, 4, 5, 5, 6, 4, 5, 5, 6, 5, 6, 6, 7,
    1, 2, 2, 3, 2, 3, 3, 4, 2, 3, 3, 4, 3, 4, 4, 5, 2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6,
    2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6, 3, 4, 4, 5, 4, 5, 5, 6, 4, 5, 5, 6, 5, 6, 6, 7,
    2, 3, 3, 4, 3, 4, 4, 5, 3, 4, 4, 5, 4, 5, 5, 6, 3, 4, 4, 5, 4, 5, 5, 6, 4, 5, 5, 6, 5, 6, 6, 7,
    3, 4, 4, 5, 4, 5, 5, 6, 4, 5, 5, 6, 5, 6, 6, 7, 4, 5, 5, 6, 5, 6, 6, 7, 5, 6, 6, 7, 6, 7, 7, 8
};

static SVM_INLINE uint8_t popcount8(uint8_t x)
{
    return SVM_FLASH_BYTE(ones_in + x);
}
#else
static SVM_INLINE uint8_t popcount8(uint8_t x)
{
    x = (uint8_t)(x - ((x >> 1) & 0x55u));
    x = (uint8_t)((x & 0x33u) + ((x >> 2) & 0x33u));
    return (uint8_t)((x + (x >> 4)) & 0x0Fu);
}
#endif

/* ---- event masks -----------------------------------------------------------------------------
 * The step's set operations (poll, occurrence, enabled set, selection) work on whole event
 * masks. When SVM_MASK_BYTES allows, a mask is a native integer (1, 2 or 3-4 bytes; up to 8 off
 * AVR, where 64-bit operations are cheap), read from the image in one go (pgm_read_word/dword
 * on AVR), so that and, or and not take a few instructions instead of byte loops. Wider builds
 * keep a byte array (in a struct, so that it is assigned and passed as a value). Images whose
 * masks are narrower than SVM_MASK_BYTES (builds without SVM_MASK_EXACT) are read
 * zero-extended. A mask's events are visited in index order with a cursor, a byte at a time:
 * zero bytes are skipped whole and no mask is shifted by a variable count, which AVR does one
 * bit at a time. Transitions (apply, weight) test single bytes of the image's masks instead. */
#if SVM_MASK_BYTES == 1
typedef uint8_t mask_t;
#elif SVM_MASK_BYTES == 2
typedef uint16_t mask_t;
#elif SVM_MASK_BYTES <= 4
typedef uint32_t mask_t;
#elif SVM_MASK_BYTES <= 8 && !defined(__AVR__)
typedef uint64_t mask_t;
#else
#define MASK_ARRAY 1
typedef struct mask {
    uint8_t b[SVM_MASK_BYTES];
} mask_t;
#endif

#ifndef MASK_ARRAY
#define MASK_ARRAY 0

/* A full-width mask at `p` in program memory (AVR), little-endian as the image stores it. */
#if defined(__AVR__) && SVM_MASK_BYTES == 1
#define FLASH_MASK(p) pgm_read_byte(p)
#elif defined(__AVR__) && SVM_MASK_BYTES == 2
#define FLASH_MASK(p) pgm_read_word(p)
#elif defined(__AVR__) && SVM_MASK_BYTES == 3
#define FLASH_MASK(p) (pgm_read_word(p) | ((uint32_t)pgm_read_byte((p) + 2) << 16))
#elif defined(__AVR__)
#define FLASH_MASK(p) pgm_read_dword(p)
#else
#define FLASH_MASK(p) 0u
#endif

/* The image's mask of `m` bytes at `p`. */
static SVM_INLINE mask_t mask_read(uint8_t source, const uint8_t *p, uint8_t m)
{
    mask_t mask = 0;
    if (m == SVM_MASK_BYTES && IN_FLASH(source)) {
        return (mask_t)FLASH_MASK(p);
    }
    for (p += m; m != 0u; m--) {
        mask = (mask_t)((mask_t)(mask << 8) | PEEK(source, --p));
    }
    return mask;
}

/* A mask kept in RAM as SVM_MASK_BYTES bytes, and back (`m` bytes). */
static SVM_INLINE mask_t mask_load(const uint8_t *bytes)
{
    mask_t mask = 0;
    uint8_t i;
    for (i = SVM_MASK_BYTES; i != 0u; i--) {
        mask = (mask_t)((mask_t)(mask << 8) | bytes[i - 1u]);
    }
    return mask;
}

static SVM_INLINE void mask_store(uint8_t *bytes, mask_t mask, uint8_t m)
{
    for (; m != 0u; m--) {
        *bytes++ = (uint8_t)mask;
        mask = (mask_t)(mask >> 8);
    }
}

static SVM_INLINE mask_t mask_and(mask_t a, mask_t b) { return (mask_t)(a & b); }
static SVM_INLINE mask_t mask_and_not(mask_t a, mask_t b) { return (mask_t)(a & (mask_t)~b); }
static SVM_INLINE mask_t mask_or_not(mask_t a, mask_t b) { return (mask_t)(a | (mask_t)~b); }
static SVM_INLINE uint8_t mask_any(mask_t a) { return a != 0u; }

/* Events 0 .. n-1 (n <= 8 * SVM_MASK_BYTES); MASK_LOW_MAX: all SVM_MAX_EVENTS, a constant. */
static mask_t mask_low(uint8_t n)
{
    mask_t mask = 0;
    for (; n >= 8u; n = (uint8_t)(n - 8u)) {
        mask = (mask_t)((mask_t)(mask << 8) | 0xFFu);
    }
    for (; n != 0u; n--) {
        mask = (mask_t)((mask_t)(mask << 1) | 1u);
    }
    return mask;
}
#define MASK_LOW_MAX ((mask_t)((((mask_t)1u << (SVM_MAX_EVENTS - 1)) << 1) - 1u))

/* Cursor over a mask's events: `rest` holds the events not visited yet, shifted down by
 * `base` (a multiple of 8). */
typedef struct cursor {
    mask_t rest;
    uint8_t base;
} cursor_t;

static SVM_INLINE void cursor_start(cursor_t *c, mask_t mask)
{
    c->rest = mask;
    c->base = 0;
}

static SVM_INLINE uint8_t cursor_any(const cursor_t *c) { return c->rest != 0u; }
static SVM_INLINE uint8_t cursor_byte(const cursor_t *c) { return (uint8_t)c->rest; }

/* Leave the current 8 events unvisited. */
static SVM_INLINE void cursor_skip_byte(cursor_t *c)
{
    c->rest = (mask_t)(c->rest >> 8);
    c->base = (uint8_t)(c->base + 8u);
}

/* Clear bit `bit` of the current byte. */
static SVM_INLINE void cursor_clear(cursor_t *c, uint8_t bit) { c->rest = (mask_t)(c->rest ^ bit); }

#else /* MASK_ARRAY */

static SVM_INLINE mask_t mask_read(uint8_t source, const uint8_t *p, uint8_t m)
{
    mask_t mask;
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        mask.b[i] = i < m ? PEEK(source, p + i) : 0u;
    }
    return mask;
}

static SVM_INLINE mask_t mask_load(const uint8_t *bytes)
{
    mask_t mask;
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        mask.b[i] = bytes[i];
    }
    return mask;
}

static SVM_INLINE void mask_store(uint8_t *bytes, mask_t mask, uint8_t m)
{
    uint8_t i;
    for (i = 0; i < m; i++) {
        bytes[i] = mask.b[i];
    }
}

static SVM_INLINE mask_t mask_and(mask_t a, mask_t b)
{
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        a.b[i] &= b.b[i];
    }
    return a;
}

static SVM_INLINE mask_t mask_and_not(mask_t a, mask_t b)
{
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        a.b[i] &= (uint8_t)~b.b[i];
    }
    return a;
}

static SVM_INLINE mask_t mask_or_not(mask_t a, mask_t b)
{
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        a.b[i] |= (uint8_t)~b.b[i];
    }
    return a;
}

static SVM_INLINE uint8_t mask_any(mask_t a)
{
    uint8_t i, any = 0;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        any |= a.b[i];
    }
    return any != 0u;
}

static mask_t mask_low(uint8_t n)
{
    mask_t mask;
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++, n = (uint8_t)(n >= 8u ? n - 8u : 0u)) {
        mask.b[i] = n >= 8u ? 0xFFu : (uint8_t)((1u << n) - 1u);
    }
    return mask;
}
#define MASK_LOW_MAX mask_low(SVM_MAX_EVENTS)

/* Cursor: the events not visited yet, and the index of the current byte. */
typedef struct cursor {
    mask_t rest;
    uint8_t at;
    uint8_t base;
} cursor_t;

static SVM_INLINE void cursor_start(cursor_t *c, mask_t mask)
{
    c->rest = mask;
    c->at = 0;
    c->base = 0;
}

static SVM_INLINE uint8_t cursor_any(const cursor_t *c) { return mask_any(c->rest); }
static SVM_INLINE uint8_t cursor_byte(const cursor_t *c) { return c->rest.b[c->at]; }

static SVM_INLINE void cursor_skip_byte(cursor_t *c)
{
    c->rest.b[c->at++] = 0;
    c->base = (uint8_t)(c->base + 8u);
}

static SVM_INLINE void cursor_clear(cursor_t *c, uint8_t bit) { c->rest.b[c->at] ^= bit; }

#endif /* MASK_ARRAY */

static SVM_INLINE uint8_t mask_count(mask_t a)
{
    cursor_t c;
    uint8_t count = 0;
    for (cursor_start(&c, a); cursor_any(&c); cursor_skip_byte(&c)) {
        count = (uint8_t)(count + popcount8(cursor_byte(&c)));
    }
    return count;
}

/* The next event of the cursor (which has one), then visited. */
static SVM_INLINE uint8_t cursor_next(cursor_t *c)
{
    uint8_t low, event;
    while ((low = cursor_byte(c)) == 0u) {
        cursor_skip_byte(c);
    }
    low = (uint8_t)(low & (uint8_t)-low);
    cursor_clear(c, low);
    for (event = c->base; low != 1u; low = (uint8_t)(low >> 1)) {
        event++;
    }
    return event;
}

/* ---- checksum and validation ------------------------------------------------------------- */

/* CRC-16/MCRF4XX a byte at a time, without a table and without branches: the byte-wise form
 * of the reflected CCITT polynomial that avr-libc's _crc_ccitt_update also uses (8 shifts and
 * xors per byte instead of 8 conditional steps). */
static SVM_INLINE uint16_t crc_byte(uint16_t crc, uint8_t byte)
{
    uint8_t d = (uint8_t)(byte ^ (uint8_t)crc);
    d = (uint8_t)(d ^ (uint8_t)(d << 4));
    return (uint16_t)((((uint16_t)d << 8) | (crc >> 8)) ^ (uint8_t)(d >> 4) ^ ((uint16_t)d << 3));
}

uint16_t svm_crc16_update(uint16_t crc, uint8_t byte)
{
    return crc_byte(crc, byte);
}

static uint16_t crc16(const uint8_t *image, uint8_t source, uint16_t length)
{
    uint16_t crc = SVM_CRC16_INIT;
    uint16_t i;
    for (i = 0; i < length; i++) {
        crc = crc_byte(crc, rd_raw(image, source, i));
    }
    return crc;
}

/* What svm_load needs to know once an image has been accepted. */
typedef struct layout {
    uint16_t states_at, targets_at, probs_at, names_at;
} layout_t;

/* Whether the event mask of `m` bytes at `at` has a bit set at or above event `e` (in its last
 * byte's padding): an event the image does not have. */
static uint8_t beyond_events(const uint8_t *image, uint8_t source, uint16_t at, uint8_t m, uint8_t e)
{
    uint8_t used = (uint8_t)(e & 7u);
    return used != 0u && (rd_raw(image, source, (uint16_t)(at + m - 1u)) >> used) != 0u;
}

/* Every index the step follows must stay inside the image, every event mask inside the image's
 * events: check them once here. */
static int check_indices(const uint8_t *image, uint8_t source, const layout_t *lay)
{
    uint8_t m = rd_raw(image, source, SVM_AT_MASK_BYTES), width = rd_raw(image, source, SVM_AT_STATE_WIDTH);
    uint8_t n = rd_raw(image, source, SVM_AT_NUM_SUPERVISORS), e = rd_raw(image, source, SVM_AT_NUM_EVENTS);
    uint16_t total_states = rd16_raw(image, source, SVM_AT_NUM_STATES);
    uint16_t total_trans = rd16_raw(image, source, SVM_AT_NUM_TRANSITIONS);
    uint16_t expected_first = 0;
    uint8_t s;
    if (beyond_events(image, source, CONTROLLABLE_AT, m, e) || beyond_events(image, source, PUBLIC_AT(m), m, e)) {
        return SVM_ERR_LAYOUT;
    }
    for (s = 0; s < n; s++) {
        uint16_t alphabet = (uint16_t)(SUPS_AT(m) + (uint16_t)s * (m + 6u));
        uint16_t at = (uint16_t)(alphabet + m);
        uint16_t first = rd16_raw(image, source, at);
        uint16_t count = rd16_raw(image, source, (uint16_t)(at + 2u));
        uint16_t init = rd16_raw(image, source, (uint16_t)(at + 4u));
        uint16_t q;
        if (first != expected_first || count == 0 || init >= count || count > total_states - first ||
            beyond_events(image, source, alphabet, m, e)) {
            return SVM_ERR_LAYOUT;
        }
        for (q = 0; q < count; q++) {
            uint16_t st = (uint16_t)(lay->states_at + (uint16_t)(first + q) * (m + 2u));
            uint16_t succ = rd16_raw(image, source, (uint16_t)(st + m));
            uint16_t defined = 0, k;
            uint8_t i;
            if (beyond_events(image, source, st, m, e)) {
                return SVM_ERR_LAYOUT;
            }
            for (i = 0; i < m; i++) {
                defined = (uint16_t)(defined + popcount8(rd_raw(image, source, (uint16_t)(st + i))));
            }
            if (succ > total_trans || defined > total_trans - succ) {
                return SVM_ERR_LAYOUT;
            }
            for (k = 0; k < defined; k++) {
                uint16_t t_at = (uint16_t)(lay->targets_at + (uint16_t)(succ + k) * width);
                uint16_t target = width == 1u ? rd_raw(image, source, t_at) : rd16_raw(image, source, t_at);
                if (target >= count) {
                    return SVM_ERR_LAYOUT;
                }
            }
        }
        expected_first = (uint16_t)(first + count);
    }
    return expected_first == total_states ? SVM_OK : SVM_ERR_LAYOUT;
}

/* Whether `c` may be part of an event name: letters, digits and '_' (the input languages' rule). */
static uint8_t name_char(uint8_t c)
{
    return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

static int validate(const uint8_t *image, uint8_t source, uint16_t length, layout_t *lay)
{
    uint8_t flags, e, n, width, m;
    uint16_t states, trans, end, i;
    uint32_t pos;
    if (image == 0 || length < SVM_MIN_IMAGE_SIZE || rd16_raw(image, source, SVM_AT_LENGTH) != length) {
        return SVM_ERR_LENGTH;
    }
    if (rd16_raw(image, source, SVM_AT_MAGIC) != (uint16_t)SVM_MAGIC ||
        rd16_raw(image, source, SVM_AT_MAGIC + 2u) != (uint16_t)(SVM_MAGIC >> 16)) {
        return SVM_ERR_MAGIC;
    }
    if (rd_raw(image, source, SVM_AT_VERSION) != SVM_FORMAT_VERSION) {
        return SVM_ERR_VERSION;
    }
    end = (uint16_t)(length - SVM_CRC_SIZE);
    if (crc16(image, source, end) != rd16_raw(image, source, end)) {
        return SVM_ERR_CRC;
    }
    flags = rd_raw(image, source, SVM_AT_FLAGS);
    e = rd_raw(image, source, SVM_AT_NUM_EVENTS);
    n = rd_raw(image, source, SVM_AT_NUM_SUPERVISORS);
    states = rd16_raw(image, source, SVM_AT_NUM_STATES);
    trans = rd16_raw(image, source, SVM_AT_NUM_TRANSITIONS);
    width = rd_raw(image, source, SVM_AT_STATE_WIDTH);
    m = rd_raw(image, source, SVM_AT_MASK_BYTES);
    if (e == 0 || n == 0 || (width != 1u && width != 2u) || m != (uint8_t)((e + 7u) / 8u) ||
        (flags & (uint8_t)~SVM_KNOWN_FLAGS) != 0u) {
        return SVM_ERR_LAYOUT;
    }
#if SVM_MASK_EXACT
    if (m != SVM_MASK_BYTES) {
        return SVM_ERR_LIMITS;
    }
#endif
    /* Section offsets in 32 bits: a corrupt header must not wrap around. */
    pos = SVM_HEADER_SIZE + 2u * (uint32_t)m + (uint32_t)n * (m + 6u);
    lay->states_at = (uint16_t)pos;
    pos += (uint32_t)states * (m + 2u);
    lay->targets_at = (uint16_t)pos;
    pos += (uint32_t)trans * width;
    lay->probs_at = 0;
    if (flags & SVM_FLAG_PROBS) {
        lay->probs_at = (uint16_t)pos;
        pos += 2u * (uint32_t)trans;
    }
    lay->names_at = 0;
    if (pos > end) {
        return SVM_ERR_LAYOUT;
    }
    if (flags & SVM_FLAG_NAMES) {
        lay->names_at = (uint16_t)pos;
        for (i = 0; i < e; i++) {
            uint32_t name_end;
            if (pos >= end) {
                return SVM_ERR_LAYOUT;
            }
            name_end = pos + 1u + rd_raw(image, source, (uint16_t)pos);
            if (name_end > end) {
                return SVM_ERR_LAYOUT;
            }
            for (pos++; pos < name_end; pos++) {
                if (!name_char(rd_raw(image, source, (uint16_t)pos))) {
                    return SVM_ERR_LAYOUT;
                }
            }
        }
    }
    if (flags & SVM_FLAG_ORDER) {     /* read by the compatibility layers only: bounds checked */
        if (pos + e + 2u * (uint32_t)states > end) {
            return SVM_ERR_LAYOUT;
        }
        for (i = 0; i < e; i++, pos++) {
            if (rd_raw(image, source, (uint16_t)pos) >= e) {
                return SVM_ERR_LAYOUT;
            }
        }
        pos += 2u * (uint32_t)states;
    }
    if (pos != end) {
        return SVM_ERR_LAYOUT;
    }
    /* (Each test is left out when the limit is the field's range: it could not fail.) */
#if SVM_MAX_EVENTS < 255
    if (e > SVM_MAX_EVENTS) {
        return SVM_ERR_LIMITS;
    }
#endif
#if SVM_MAX_SUPERVISORS < 255
    if (n > SVM_MAX_SUPERVISORS) {
        return SVM_ERR_LIMITS;
    }
#endif
#if SVM_MAX_STATES < 65535
    if (states > SVM_MAX_STATES) {
        return SVM_ERR_LIMITS;
    }
#endif
    return check_indices(image, source, lay);
}

/* Whether this build reads images from `source` (SVM_IMAGE_SOURCES). */
static uint8_t readable(uint8_t source)
{
#if defined(__AVR__)
    switch (SVM_IMAGE_SOURCES) {
    case SVM_FLASH_ONLY:
        return source == SVM_SOURCE_FLASH;
    case SVM_RAM_ONLY:
        return source == SVM_SOURCE_RAM;
    case SVM_ANY_SOURCE:
        return 1;
    default:
        return source != SVM_SOURCE_EEPROM;
    }
#else
    return source != SVM_SOURCE_EEPROM;
#endif
}

int svm_validate(const uint8_t *image, uint16_t length, uint8_t source)
{
    layout_t lay;
    return readable(source) ? validate(image, source, length, &lay) : SVM_ERR_SOURCE;
}

/* ---- life cycle ---------------------------------------------------------------------------- */

void svm_init(svm_vm_t *vm)
{
    uint8_t *raw = (uint8_t *)vm;
    uint16_t i;
    for (i = 0; i < sizeof *vm; i++) {
        raw[i] = 0;
    }
    vm->image = 0;
    vm->bindings = 0;
    vm->dispatch = 0;
    vm->chooser = 0;
    vm->chooser_ctx = 0;
    vm->on_violation = 0;
    vm->priority = 0;
    vm->priority_by_name = 0;
    vm->seed = SVM_DEFAULT_SEED;
    vm->rng = SVM_DEFAULT_SEED;
}

void svm_reset(svm_vm_t *vm)
{
    uint8_t s;
    for (s = 0; s < vm->num_supervisors; s++) {
        uint16_t sup = (uint16_t)SUP_AT(vm, s);
        vm->state[s] = (svm_state_t)(RD16(vm, sup + vm->mask_bytes) + RD16(vm, sup + vm->mask_bytes + 4u));
    }
    for (s = 0; s < SVM_MASK_BYTES; s++) {
        vm->previous[s] = 0;
    }
    vm->violations = 0;
    vm->rng = vm->seed ? vm->seed : SEED_FOR_ZERO;
}

/* Offset of the event's name record (length byte, then the name) in an image. */
static uint16_t name_at(const uint8_t *image, uint8_t source, uint16_t names_at, uint8_t event)
{
    uint16_t pos = names_at;
    uint8_t i;
    for (i = 0; i < event; i++) {
        pos = (uint16_t)(pos + 1u + rd_raw(image, source, pos));
    }
    return pos;
}

/* Index, in a new image (validated, not yet loaded), of the old image's event of the same
 * name; -1 if it has none. Either image may be in flash, RAM or EEPROM. */
static int find_in_new(const svm_vm_t *vm, const uint8_t *image, uint8_t source,
                       const layout_t *lay, uint8_t old_event)
{
    uint16_t old_pos = name_at(vm->image, vm->source, vm->names_at, old_event);
    uint8_t old_len = RD(vm, old_pos);
    uint8_t e, count = rd_raw(image, source, SVM_AT_NUM_EVENTS), i;
    uint16_t pos = lay->names_at;
    for (e = 0; e < count; e++) {
        uint8_t len = rd_raw(image, source, pos);
        if (len == old_len) {
            for (i = 0; i < len; i++) {
                if (rd_raw(image, source, (uint16_t)(pos + 1u + i)) != RD(vm, old_pos + 1u + i)) {
                    break;
                }
            }
            if (i == len) {
                return e;
            }
        }
        pos = (uint16_t)(pos + 1u + len);
    }
    return -1;
}

static uint8_t is_bound(const svm_binding_t *b)
{
    return b->action != 0 || b->check != 0 || b->data != 0;
}

/* Swap: move each runtime binding from its old event index to the index its name has in the
 * new image, in place. The map is injective (names are unique), so carrying a binding to its
 * new slot, picking up the binding that slot held and carrying that on, places every binding
 * once, whether its moves form a chain or a cycle. */
static int rebind_by_name(svm_vm_t *vm, const uint8_t *image, uint8_t source, const layout_t *lay)
{
    uint8_t map[SVM_MAX_EVENTS] = {0};     /* zeroed only for gcc's flow analysis: entries past */
    uint8_t moved[SVM_MASK_BYTES];          /* `limit` are never read (-Wmaybe-uninitialized at */
    uint8_t e, cap = vm->bindings_cap;      /* SVM_MAX_EVENTS=1 on arm-none-eabi-gcc)            */
    uint8_t limit = vm->num_events < cap ? vm->num_events : cap;
    for (e = 0; e < SVM_MASK_BYTES; e++) {
        moved[e] = 0;
    }
    for (e = 0; e < limit; e++) {
        map[e] = 0xFFu;
        if (is_bound(&vm->bindings[e])) {
            int to = lay->names_at == 0 ? -1 : find_in_new(vm, image, source, lay, e);
            if (to < 0 || to >= cap) {
                return SVM_ERR_NAMES;
            }
            map[e] = (uint8_t)to;
        }
    }
    for (e = 0; e < limit; e++) {
        svm_binding_t carry;
        uint8_t to;
        if (map[e] == 0xFFu || (moved[e >> 3] & (1u << (e & 7u)))) {
            continue;
        }
        carry = vm->bindings[e];
        vm->bindings[e].action = 0;
        vm->bindings[e].check = 0;
        vm->bindings[e].data = 0;
        moved[e >> 3] = (uint8_t)(moved[e >> 3] | (1u << (e & 7u)));
        to = map[e];
        while (to < limit && map[to] != 0xFFu && !(moved[to >> 3] & (1u << (to & 7u)))) {
            svm_binding_t held = vm->bindings[to];
            vm->bindings[to] = carry;
            moved[to >> 3] = (uint8_t)(moved[to >> 3] | (1u << (to & 7u)));
            carry = held;
            to = map[to];
        }
        vm->bindings[to] = carry;
    }
    return SVM_OK;
}

/* Swap: the priority list of svm_bind_priority follows its events' names into the new image;
 * with `write` 0 only checks that every name is there, so that a refusal changes nothing. */
static int rebind_priority(svm_vm_t *vm, const uint8_t *image, uint8_t source, const layout_t *lay,
                           uint8_t write)
{
    uint8_t k;
    for (k = 0; k < vm->priority_count; k++) {
        int to = -1;
        if (vm->priority_by_name[k] < vm->num_events) {
            to = lay->names_at == 0 ? -1 : find_in_new(vm, image, source, lay, vm->priority_by_name[k]);
            if (to < 0) {
                return SVM_ERR_NAMES;
            }
        }
        if (write) {
            vm->priority_by_name[k] = to < 0 ? 0xFFu : (uint8_t)to;
        }
    }
    return SVM_OK;
}

static int load(svm_vm_t *vm, const uint8_t *image, uint16_t length, uint8_t source)
{
    layout_t lay;
    uint8_t rebind = vm->image != 0 && vm->names_at != 0;
    int result = validate(image, source, length, &lay);
    if (result != SVM_OK) {
        return result;
    }
    if (rebind && vm->priority_by_name != 0 && (result = rebind_priority(vm, image, source, &lay, 0)) != SVM_OK) {
        return result;
    }
    if (rebind && vm->bindings != 0 && (result = rebind_by_name(vm, image, source, &lay)) != SVM_OK) {
        return result;
    }
    if (rebind && vm->priority_by_name != 0) {
        (void)rebind_priority(vm, image, source, &lay, 1);
    }
    vm->image = image;
    vm->source = source;
    vm->states_at = lay.states_at;
    vm->targets_at = lay.targets_at;
    vm->probs_at = lay.probs_at;
    vm->names_at = lay.names_at;
    vm->num_events = RD(vm, SVM_AT_NUM_EVENTS);
    vm->num_supervisors = RD(vm, SVM_AT_NUM_SUPERVISORS);
    vm->width = RD(vm, SVM_AT_STATE_WIDTH);
    vm->mask_bytes = RD(vm, SVM_AT_MASK_BYTES);
    svm_reset(vm);
    return SVM_OK;
}

int svm_load(svm_vm_t *vm, const uint8_t *image, uint16_t length)
{
    return readable(SVM_SOURCE_RAM) ? load(vm, image, length, SVM_SOURCE_RAM) : SVM_ERR_SOURCE;
}

int svm_load_P(svm_vm_t *vm, const uint8_t *image, uint16_t length)
{
#if defined(__AVR__)
    return readable(SVM_SOURCE_FLASH) ? load(vm, image, length, SVM_SOURCE_FLASH) : SVM_ERR_SOURCE;
#else
    return load(vm, image, length, SVM_SOURCE_RAM);
#endif
}

int svm_load_E(svm_vm_t *vm, const uint8_t *image, uint16_t length)
{
    return readable(SVM_SOURCE_EEPROM) ? load(vm, image, length, SVM_SOURCE_EEPROM) : SVM_ERR_SOURCE;
}

void svm_set_options(svm_vm_t *vm, uint8_t options, uint32_t seed)
{
    vm->options = options;
    vm->seed = seed;
}

/* ---- callbacks ----------------------------------------------------------------------------- */

void svm_set_bindings(svm_vm_t *vm, svm_binding_t *table, uint8_t cap)
{
    uint8_t e;
    for (e = 0; e < cap; e++) {
        table[e].action = 0;
        table[e].check = 0;
        table[e].data = 0;
    }
    vm->bindings = table;
    vm->bindings_cap = cap;
}

int svm_bind(svm_vm_t *vm, uint8_t event, svm_action_fn action, svm_check_fn check, void *data)
{
    if (vm->bindings == 0) {
        return SVM_ERR_NO_BINDINGS;
    }
    if (vm->image == 0 || event >= vm->num_events || event >= vm->bindings_cap ||
        (check != 0 && svm_is_controllable(vm, event))) {
        return SVM_ERR_EVENT;
    }
    if (action != 0) {
        vm->bindings[event].action = action;
    }
    if (check != 0) {
        vm->bindings[event].check = check;
    }
    vm->bindings[event].data = data;
    return SVM_OK;
}

void svm_set_dispatch(svm_vm_t *vm, svm_dispatch_fn dispatch)
{
    vm->dispatch = dispatch;
}

void svm_set_chooser(svm_vm_t *vm, svm_chooser_fn chooser, void *ctx)
{
    vm->chooser = chooser;
    vm->chooser_ctx = ctx;
}

void svm_set_priority(svm_vm_t *vm, const uint8_t *events, uint8_t count)
{
    vm->priority = events;
    vm->priority_by_name = 0;
    vm->priority_count = events != 0 ? count : 0u;
}

void svm_bind_priority(svm_vm_t *vm, uint8_t *events, uint8_t count)
{
    svm_set_priority(vm, events, count);
    vm->priority_by_name = events;
}

void svm_set_on_violation(svm_vm_t *vm, svm_violation_fn hook)
{
    vm->on_violation = hook;
}

static void run_action(svm_vm_t *vm, uint8_t event)
{
    if (vm->bindings != 0 && event < vm->bindings_cap && vm->bindings[event].action != 0) {
        vm->bindings[event].action(vm->bindings[event].data);
    } else if (vm->dispatch != 0) {
        (void)vm->dispatch(vm, event, SVM_OP_ACTION);
    }
}

/* ---- the step ------------------------------------------------------------------------------ */

uint32_t svm_random(svm_vm_t *vm)
{
    uint32_t x = vm->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    vm->rng = x;
    return x;
}

/* The hot functions below work on pointers into the image, copied with the header fields into
 * locals: a store into vm->state (bytes) may alias any field, which would otherwise be reloaded
 * at every read. */

/* Index (into the target/probability sections) of the transition on the event (`byte`,
 * `bit`) from the state whose record is `st` and whose `defined` mask byte `byte` is
 * `defined` (it has the event): the state's first successor plus the number of its events
 * below this one. Only the mask bytes up to the event's are read. */
static SVM_INLINE uint16_t successor(uint8_t src, const uint8_t *st, uint8_t m, uint8_t defined, uint8_t byte,
                                     uint8_t bit)
{
    uint8_t rank = popcount8((uint8_t)(defined & (bit - 1u)));
    const uint8_t *below;
    for (below = st; byte != 0u; below++, byte--) {
        rank = (uint8_t)(rank + popcount8(PEEK(src, below)));
    }
    return (uint16_t)(peek16(src, st + m) + rank);
}

static void violation(svm_vm_t *vm, uint8_t event, uint8_t s)
{
    if (vm->violations != SVM_MAX_VIOLATIONS) {
        vm->violations++;
    }
    if (vm->on_violation != 0) {
        vm->on_violation(vm, event, s);
    }
}

/* Docs/semantics.md step 3: move every supervisor that has the event, count violations, then
 * run the event's action. Supervisor records are walked in order, without multiplications.
 * `m` is the mask width: see step_m for why it is a parameter. */
static SVM_INLINE void apply(svm_vm_t *vm, uint8_t event, uint8_t byte, uint8_t bit, uint8_t m)
{
    const uint8_t *img = vm->image;
    const uint8_t *states = img + vm->states_at, *targets = img + vm->targets_at;
    const uint8_t *sup = img + SUPS_AT(m);
    svm_state_t *state = vm->state;
    uint8_t src = vm->source, n = vm->num_supervisors, narrow = vm->width == 1u, s;
    for (s = 0; s < n; s++, sup += SUP_SIZE(m)) {
        const uint8_t *st;
        uint8_t defined;
        uint16_t t, local;
        if (!(PEEK(src, sup + byte) & bit)) {
            continue;
        }
        st = states + (uint16_t)state[s] * STATE_SIZE(m);
        defined = PEEK(src, st + byte);
        if (!(defined & bit)) {
            violation(vm, event, s);
            continue;
        }
        t = successor(src, st, m, defined, byte, bit);
        local = narrow ? PEEK(src, targets + t) : peek16(src, targets + 2u * t);
        state[s] = (svm_state_t)(peek16(src, sup + m) + local);
    }
    run_action(vm, event);
}

/* The enabled controllable events among `candidates` (docs/semantics.md step 5). */
static SVM_INLINE mask_t enabled_set(const svm_vm_t *vm, mask_t candidates, uint8_t m)
{
    const uint8_t *img = vm->image, *sup = img + SUPS_AT(m), *states = img + vm->states_at;
    const svm_state_t *state = vm->state;
    uint8_t src = vm->source, s;
    for (s = vm->num_supervisors; s != 0u; s--, sup += SUP_SIZE(m)) {
        const uint8_t *st = states + (uint16_t)*state++ * STATE_SIZE(m);
        candidates = mask_and(candidates, mask_or_not(mask_read(src, st, m), mask_read(src, sup, m)));
    }
    return candidates;
}

/* The events 0 .. E-1 of the loaded image. */
static SVM_INLINE mask_t valid_events(const svm_vm_t *vm)
{
    return vm->num_events == SVM_MAX_EVENTS ? MASK_LOW_MAX : mask_low(vm->num_events);
}

static SVM_INLINE mask_t enabled_m(const svm_vm_t *vm, uint8_t m)
{
    mask_t controllable = mask_read(vm->source, vm->image + CONTROLLABLE_AT, m);
    return enabled_set(vm, mask_and(controllable, valid_events(vm)), m);
}

uint8_t svm_enabled(const svm_vm_t *vm, uint8_t *enabled)
{
    mask_t mask;
    if (vm->image == 0) {
        return 0;
    }
#if !SVM_MASK_EXACT
    if (vm->mask_bytes != SVM_MASK_BYTES) {
        mask = enabled_m(vm, MASK_WIDTH(vm->mask_bytes));
    } else
#endif
    {
        mask = enabled_m(vm, SVM_MASK_BYTES);
    }
    mask_store(enabled, mask, vm->mask_bytes);
    return mask_count(mask);
}

uint32_t svm_weight(const svm_vm_t *vm, uint8_t event)
{
    const uint8_t *img = vm->image, *sup, *states, *probs;
    uint32_t weight = Q15_ONE;
    uint8_t src = vm->source, m = vm->mask_bytes, byte = (uint8_t)(event >> 3), bit = (uint8_t)(1u << (event & 7u)), s;
    if (vm->probs_at == 0) {
        return weight;
    }
    sup = img + SUPS_AT(m);
    states = img + vm->states_at;
    probs = img + vm->probs_at;
    for (s = 0; s < vm->num_supervisors; s++, sup += SUP_SIZE(m)) {
        const uint8_t *st = states + (uint16_t)vm->state[s] * STATE_SIZE(m);
        uint8_t defined = PEEK(src, st + byte);
        if ((PEEK(src, sup + byte) & bit) && (defined & bit)) {
            weight = (weight * peek16(src, probs + 2u * successor(src, st, m, defined, byte, bit))) >> 15;
        }
    }
    return weight;
}

uint8_t svm_mask_nth(const uint8_t *mask, uint8_t bytes, uint8_t n)
{
    uint8_t i, bit;
    for (i = 0; i < bytes; i++) {
        uint8_t ones = popcount8(mask[i]);
        if (n >= ones) {
            n = (uint8_t)(n - ones);
            continue;
        }
        for (bit = 0; bit < 8u; bit++) {
            if (mask[i] & (1u << bit)) {
                if (n == 0) {
                    return (uint8_t)(8u * i + bit);
                }
                n--;
            }
        }
    }
    return 0xFFu;
}

/* The `n`-th event (from 0) of `mask`, which has more than n: whole bytes are counted first. */
static uint8_t nth_event(mask_t mask, uint8_t n)
{
    cursor_t c;
    uint8_t ones, event;
    cursor_start(&c, mask);
    while (n >= (ones = popcount8(cursor_byte(&c)))) {
        n = (uint8_t)(n - ones);
        cursor_skip_byte(&c);
    }
    do {
        event = cursor_next(&c);
    } while (n-- != 0u);
    return event;
}

/* floor(((r >> 16) * count) / 65536) (docs/semantics.md, policy uniform) with 8 x 8-bit
 * products: with h = r >> 16 = 256 hi + lo, h * count / 65536 = (hi * count + lo * count / 256)
 * / 256, each division a floor. */
static uint8_t uniform_index(uint32_t r, uint8_t count)
{
    uint8_t hi = (uint8_t)(r >> 24), lo = (uint8_t)(r >> 16);
    uint16_t low_part = (uint16_t)((uint16_t)lo * count) >> 8;
    return (uint8_t)(((uint16_t)((uint16_t)hi * count) + low_part) >> 8);
}

/* Whether event `e` (< E) is in the byte mask `bytes`. */
static uint8_t has_event(const uint8_t *bytes, uint8_t e)
{
    return (uint8_t)(((unsigned)bytes[e >> 3] >> (e & 7u)) & 1u);
}

/* Docs/semantics.md "Selection policies"; `count` >= 1. Returns 0xFF for no event. */
static uint8_t select_event(svm_vm_t *vm, mask_t enabled, uint8_t count)
{
    uint8_t policy = (uint8_t)(vm->options & SVM_POLICY_MASK), bytes[SVM_MASK_BYTES], e;
    if (policy == SVM_POLICY_LEARNED || policy == SVM_POLICY_FIRST) {
        mask_store(bytes, enabled, vm->mask_bytes);
    }
    if (policy == SVM_POLICY_LEARNED) {
        if (vm->chooser == 0) {
            return 0xFFu;
        }
        e = vm->chooser(vm, bytes, count, vm->chooser_ctx);
        return (e < vm->num_events && has_event(bytes, e)) ? e : 0xFFu;
    }
    if (policy == SVM_POLICY_FIRST) {
        uint8_t k;
        for (k = 0; k < vm->priority_count; k++) {
            e = vm->priority[k];
            if (e < vm->num_events && has_event(bytes, e)) {
                return e;
            }
        }
        return nth_event(enabled, 0);
    }
    if (count == 1u) {
        return nth_event(enabled, 0);
    }
    if (policy == SVM_POLICY_WEIGHTED) {
        uint32_t total = 0, pick;
        cursor_t c;
        for (cursor_start(&c, enabled); cursor_any(&c);) {
            total += svm_weight(vm, cursor_next(&c));
        }
        if (total != 0) {
            pick = svm_random(vm) % total;
            for (cursor_start(&c, enabled); cursor_any(&c);) {
                uint32_t w;
                e = cursor_next(&c);
                w = svm_weight(vm, e);
                if (pick < w) {
                    return e;
                }
                pick -= w;
            }
        }
    }
    return nth_event(enabled, uniform_index(svm_random(vm), count));
}

/* Docs/semantics.md step 1: the check values of the uncontrollable events, in input order
 * (`first`: the public ones, then `second`: the private ones). The binding table and dispatch
 * are read once per step (callbacks must not rebind during a step). */
static SVM_INLINE mask_t poll(svm_vm_t *vm, mask_t first, mask_t second)
{
    const svm_binding_t *bindings = vm->bindings;
    svm_dispatch_fn dispatch = vm->dispatch;
    uint8_t cap = bindings != 0 ? vm->bindings_cap : 0u, pass, i, current[SVM_MASK_BYTES];
    cursor_t c;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        current[i] = 0;
    }
    for (pass = 0, cursor_start(&c, first); pass < 2u; pass++, cursor_start(&c, second)) {
        for (; cursor_any(&c); cursor_skip_byte(&c)) {
            uint8_t todo = cursor_byte(&c), bit = 1, event = c.base, occurred = 0;
            for (; todo != 0u; todo = (uint8_t)(todo >> 1), bit = (uint8_t)(bit << 1), event++) {
                uint8_t occurs;
                if (!(todo & 1u)) {
                    continue;
                }
                if (event < cap && bindings[event].check != 0) {
                    occurs = bindings[event].check(bindings[event].data) != 0;
                } else {
                    occurs = dispatch != 0 && dispatch(vm, event, SVM_OP_CHECK) != 0;
                }
                if (occurs) {
                    occurred |= bit;
                }
            }
            current[c.base >> 3] |= occurred;
        }
    }
    return mask_load(current);
}

/* The step for masks of `m` bytes. Called with the compile-time SVM_MASK_BYTES when the image's
 * masks have exactly that width (builds with the model's exact limits): the compiler then
 * folds the record sizes and reads each mask in one go. */
static SVM_INLINE uint8_t step_m(svm_vm_t *vm, uint8_t m)
{
    const uint8_t *img = vm->image;
    uint8_t src = vm->source, options = vm->options, fired = 0, pass, count;
    mask_t valid = valid_events(vm);
    mask_t controllable = mask_and(mask_read(src, img + CONTROLLABLE_AT, m), valid);
    mask_t public_mask = mask_read(src, img + PUBLIC_AT(m), m);
    mask_t uncontrollable = mask_and_not(valid, controllable);
    /* 1. Poll, in input order: public uncontrollable events, then private ones. 2. Occurrence. */
    mask_t current = poll(vm, mask_and(uncontrollable, public_mask), mask_and_not(uncontrollable, public_mask));
    mask_t occurring = current;
    cursor_t inputs;
    if (options & SVM_INPUTS_EDGE) {
        occurring = mask_and_not(current, mask_load(vm->previous));
    }
    mask_store(vm->previous, current, SVM_MASK_BYTES);
    /* 3. The occurring events in input order, public then private. */
    for (pass = 0, cursor_start(&inputs, mask_and(occurring, public_mask)); pass < 2u;
         pass++, cursor_start(&inputs, mask_and_not(occurring, public_mask))) {
        for (; cursor_any(&inputs); cursor_skip_byte(&inputs)) {
            uint8_t todo = cursor_byte(&inputs), bit = 1, event = inputs.base;
            for (; todo != 0u; todo = (uint8_t)(todo >> 1), bit = (uint8_t)(bit << 1), event++) {
                if (todo & 1u) {
                    apply(vm, event, (uint8_t)(inputs.base >> 3), bit, m);
                    fired++;
                }
            }
        }
    }
    /* 4. Control phase (with if-quiet, none after an input); 5-6: enabled set, selection. */
    if (!(mask_any(occurring) && (options & SVM_CONTROL_IF_QUIET))) {
        mask_t enabled = enabled_set(vm, controllable, m);
        uint8_t event;
        if ((count = mask_count(enabled)) != 0u && (event = select_event(vm, enabled, count)) != 0xFFu) {
            apply(vm, event, (uint8_t)(event >> 3), (uint8_t)(1u << (event & 7u)), m);
            fired++;
        }
    }
    return fired;
}

uint8_t svm_step(svm_vm_t *vm)
{
    if (vm->image == 0) {
        return 0;
    }
#if !SVM_MASK_EXACT
    if (vm->mask_bytes != SVM_MASK_BYTES) {
        return step_m(vm, MASK_WIDTH(vm->mask_bytes));
    }
#endif
    return step_m(vm, SVM_MASK_BYTES);
}

/* ---- inspection ---------------------------------------------------------------------------- */

uint8_t svm_num_events(const svm_vm_t *vm)
{
    return vm->num_events;
}

uint8_t svm_num_supervisors(const svm_vm_t *vm)
{
    return vm->num_supervisors;
}

uint8_t svm_mask_bytes(const svm_vm_t *vm)
{
    return vm->mask_bytes;
}

uint16_t svm_first_state(const svm_vm_t *vm, uint8_t supervisor)
{
    if (vm->image == 0 || supervisor >= vm->num_supervisors) {
        return 0;
    }
    return RD16(vm, SUP_AT(vm, supervisor) + vm->mask_bytes);
}

uint16_t svm_state(const svm_vm_t *vm, uint8_t supervisor)
{
    if (vm->image == 0 || supervisor >= vm->num_supervisors) {
        return 0;
    }
    return (uint16_t)(vm->state[supervisor] - svm_first_state(vm, supervisor));
}

uint16_t svm_global_state(const svm_vm_t *vm, uint8_t supervisor)
{
    return (vm->image == 0 || supervisor >= vm->num_supervisors) ? 0u : vm->state[supervisor];
}

uint16_t svm_num_states(const svm_vm_t *vm)
{
    return vm->image == 0 ? 0u : RD16(vm, SVM_AT_NUM_STATES);
}

uint32_t svm_violations(const svm_vm_t *vm)
{
    return vm->violations;
}

uint8_t svm_is_controllable(const svm_vm_t *vm, uint8_t event)
{
    return (uint8_t)(event < vm->num_events && (RD(vm, CONTROLLABLE_AT + (event >> 3)) & (1u << (event & 7u))));
}

uint8_t svm_is_public(const svm_vm_t *vm, uint8_t event)
{
    return (uint8_t)(event < vm->num_events &&
                     (RD(vm, PUBLIC_AT(vm->mask_bytes) + (event >> 3)) & (1u << (event & 7u))));
}

int svm_event_index(const svm_vm_t *vm, const char *name)
{
    uint16_t pos = vm->names_at;
    uint8_t e, i;
    if (vm->image == 0 || pos == 0 || name == 0) {
        return -1;
    }
    if (name[0] == 'E' && name[1] == 'V' && name[2] == '_') {
        name += 3;
    }
    for (e = 0; e < vm->num_events; e++) {
        uint8_t len = RD(vm, pos);
        for (i = 0; i < len && name[i] != '\0'; i++) {
            if ((uint8_t)name[i] != RD(vm, pos + 1u + i)) {
                break;
            }
        }
        if (i == len && name[i] == '\0') {
            return e;
        }
        pos = (uint16_t)(pos + 1u + len);
    }
    return -1;
}

uint8_t svm_image_byte(const svm_vm_t *vm, uint16_t at)
{
    return RD(vm, at);
}

uint8_t svm_has_names(const svm_vm_t *vm)
{
    return (uint8_t)(vm->image != 0 && vm->names_at != 0);
}

uint8_t svm_event_name(const svm_vm_t *vm, uint8_t event, char *buf, uint8_t cap)
{
    uint16_t pos;
    uint8_t len, i;
    if (cap != 0u) {
        buf[0] = '\0';
    }
    if (vm->image == 0 || vm->names_at == 0 || event >= vm->num_events) {
        return 0;
    }
    pos = name_at(vm->image, vm->source, vm->names_at, event);
    len = RD(vm, pos);
    for (i = 0; i < len && (uint16_t)i + 1u < cap; i++) {
        buf[i] = (char)RD(vm, pos + 1u + i);
    }
    if (cap != 0u) {
        buf[i] = '\0';
    }
    return len;
}
