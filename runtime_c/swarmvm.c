/*
 * swarmvm C VM core (see swarmvm.h). The tables are read in place from the image; a
 * transition is found with the state's `defined` mask and a popcount (docs/image-format.md),
 * so a step costs a few mask operations per supervisor whatever the automata's size.
 */
#include "swarmvm.h"

/* Inlining hint for the step's helpers (C99 `inline` on a static function). */
#define SVM_INLINE inline

/* The mask and cursor helpers and the enabled set: in the minimal profile always inlined, so
 * that a cursor lives in registers and, for one-byte masks, its byte loops fold away (GCC's -Os
 * otherwise keeps them as functions and the cursors on the stack; benchmarks/flash_vs_published.py
 * measured it smaller and faster); elsewhere a hint, as the other helpers (other builds'
 * code is unchanged by it). */
#if defined(SVM_TRUSTED_IMAGE) && defined(__GNUC__)
#define SVM_MASK_INLINE inline __attribute__((always_inline))
#else
#define SVM_MASK_INLINE SVM_INLINE
#endif

/* The minimal profile with masks of one or two bytes visits a mask's events one bit at a time
 * over the whole mask (a shift of one or two bytes per event), instead of a byte at a time:
 * fewer instructions and no mask kept on the stack. */
#if defined(SVM_TRUSTED_IMAGE) && SVM_MASK_BYTES <= 2
#define FLAT_MASKS 1
#else
#define FLAT_MASKS 0
#endif

/* The step's counters (events, passes, events fired): with flat masks the fastest type of at
 * least 8 bits, a register on ARM (no truncation after each increment) and a byte on AVR;
 * elsewhere a byte, as always. */
#if FLAT_MASKS
typedef uint_fast8_t count_t;
#else
typedef uint8_t count_t;
#endif

/* The transition code (fire), called once in the step: a function on the bare-metal Cortex-M4
 * (CapBot, -Os), where inlining it into the step costs instructions per step on the models with
 * several supervisors; inlined elsewhere (docs/footprint.md, "Cost per step";
 * benchmarks/m4_cycles.py). */
#if defined(__GNUC__) && defined(__arm__) && !defined(__linux__)
#define SVM_FIRE __attribute__((noinline))
#else
#define SVM_FIRE SVM_INLINE
#endif

/* Load-time code (checks, life cycle, names, bindings) on a microcontroller: optimised for
 * size whatever the build's -O, so that -O3 (kilolib's flags) spends flash on the step only.
 * GCC compiles a `cold` function as if with -Os. */
#if defined(__GNUC__) && (defined(__AVR__) || (defined(__arm__) && !defined(__linux__)))
#define SVM_COLD __attribute__((cold, noinline))
#else
#define SVM_COLD
#endif

/* A swap moves what is bound by event name (runtime bindings, svm_bind_priority's list). A
 * trusted build (SVM_TRUSTED_IMAGE) has one image, so a swap never changes an event's index. */
#ifdef SVM_TRUSTED_IMAGE
#define REBIND_BY_NAME 0
#else
#define REBIND_BY_NAME (SVM_WITH_NAMES && (SVM_WITH_BINDINGS || SVM_WITH_FIRST))
#endif

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

/*@ requires \valid_read(image + at);
    assigns \nothing; */
static SVM_COLD uint8_t rd_raw(const uint8_t *image, uint8_t source, uint16_t at)
{
    return (uint8_t)READ(image, source, at);
}

//@ assigns \nothing;
static SVM_COLD uint16_t rd16_raw(const uint8_t *image, uint8_t source, uint16_t at)
{
    return (uint16_t)(rd_raw(image, source, at) | ((uint16_t)rd_raw(image, source, (uint16_t)(at + 1u)) << 8));
}

#define RD(vm, at) rd_raw((vm)->image, VM_SOURCE(vm), (uint16_t)(at))
#define RD16(vm, at) rd16_raw((vm)->image, VM_SOURCE(vm), (uint16_t)(at))

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
#define SUP_AT(vm, s) (SUPS_AT(VM_MASK_BYTES(vm)) + (uint16_t)(s) * SUP_SIZE(VM_MASK_BYTES(vm)))
/* vm->state[s] is the supervisor's *global* state number: its record is at
 * states_at + state * STATE_SIZE(m), found without reading the supervisor's first state. */

/* The step's view of the loaded image's counts and section offsets. A trusted build runs an
 * image of exactly its limits (its load refuses any other), so there they are constants the
 * compiler folds into the step: fewer loads, no multiplication at run time, less flash. */
#ifdef SVM_TRUSTED_IMAGE
#define VM_EVENTS(vm) ((void)(vm), (uint8_t)SVM_MAX_EVENTS)
#define VM_MASK_BYTES(vm) ((void)(vm), (uint8_t)SVM_MASK_BYTES)
#define VM_SUPERVISORS(vm) ((void)(vm), (uint8_t)SVM_MAX_SUPERVISORS)
#define TRUSTED_STATES_AT ((uint16_t)(SUPS_AT(SVM_MASK_BYTES) + SVM_MAX_SUPERVISORS * SUP_SIZE(SVM_MASK_BYTES)))
#define TRUSTED_TARGETS_AT ((uint16_t)(TRUSTED_STATES_AT + (uint32_t)SVM_MAX_STATES * STATE_SIZE(SVM_MASK_BYTES)))
#define VM_STATES_AT(vm) ((void)(vm), TRUSTED_STATES_AT)
#define VM_TARGETS_AT(vm) ((void)(vm), TRUSTED_TARGETS_AT)
#if SVM_MAX_STATES <= 256
#define VM_NARROW(vm) ((void)(vm), 1u)     /* no supervisor has more than 256 states */
#else
#define VM_NARROW(vm) ((vm)->width == 1u)
#endif
#else
#define VM_EVENTS(vm) ((vm)->num_events)
#define VM_MASK_BYTES(vm) ((vm)->mask_bytes)
#define VM_SUPERVISORS(vm) ((vm)->num_supervisors)
#define VM_STATES_AT(vm) ((vm)->states_at)
#define VM_TARGETS_AT(vm) ((vm)->targets_at)
#define VM_NARROW(vm) ((vm)->width == 1u)
#endif

/* The step's image (the loaded one: its own symbol as a constant measured larger in the step)
 * and where it lives: in the minimal profile always program memory on AVR, a plain read
 * elsewhere, a constant. */
#define VM_IMAGE(vm) ((vm)->image)
#ifdef SVM_TRUSTED_IMAGE
#if defined(__AVR__)
#define VM_SOURCE(vm) ((void)(vm), (uint8_t)SVM_SOURCE_FLASH)
#else
#define VM_SOURCE(vm) ((void)(vm), (uint8_t)SVM_SOURCE_RAM)
#endif
#else
#define VM_SOURCE(vm) ((vm)->source)
#endif

/* The counts the inspection functions give: the image's, 0 before a load. The profile keeps no
 * copy of them in the VM (its image's are the build's limits). */
#ifdef SVM_TRUSTED_IMAGE
#define LOADED_EVENTS(vm) ((vm)->image != 0 ? (uint8_t)SVM_MAX_EVENTS : (uint8_t)0u)
#define LOADED_SUPERVISORS(vm) ((vm)->image != 0 ? (uint8_t)SVM_MAX_SUPERVISORS : (uint8_t)0u)
#define LOADED_MASK_BYTES(vm) ((vm)->image != 0 ? (uint8_t)SVM_MASK_BYTES : (uint8_t)0u)
#else
#define LOADED_EVENTS(vm) ((vm)->num_events)
#define LOADED_SUPERVISORS(vm) ((vm)->num_supervisors)
#define LOADED_MASK_BYTES(vm) ((vm)->mask_bytes)
#endif

/* The step's options: the build's (SVM_TRUSTED_OPTIONS, the minimal profile), or the VM's. */
#ifdef SVM_TRUSTED_OPTIONS
#define VM_OPTIONS(vm) ((void)(vm), (uint8_t)(SVM_TRUSTED_OPTIONS))
#else
#define VM_OPTIONS(vm) ((vm)->options)
#endif

/* A loaded image's mask width, clamped to 1..SVM_MASK_BYTES for the compiler's sake (load has
 * checked it already), so that loops over it provably stay inside the VM's mask arrays. */
#define MASK_WIDTH(m) ((uint8_t)((m) - 1u) < SVM_MASK_BYTES ? (uint8_t)(m) : (uint8_t)1u)

/* Set bits of a byte. AVR shifts one bit per instruction, so there a table in flash (256 B,
 * SVM_POPCOUNT_TABLE) does it in one lpm; elsewhere bit arithmetic. Smaller tables (a nibble's,
 * or 7 bits' plus the top bit) save little flash, their code growing, and slow the step
 * (docs/footprint.md, "Cost per step"). */
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

//@ assigns \nothing;
static SVM_INLINE uint8_t popcount8(uint8_t x)
{
    return SVM_FLASH_BYTE(ones_in + x);
}
#elif defined(SVM_TRUSTED_IMAGE) && ((defined(__arm__) && !defined(__linux__)) || defined(__AVR__))
/* The minimal profile on AVR and bare-metal ARM: one bit cleared per set bit (the fewest bytes;
 * the masks it counts, below an event or of a state, have few bits). */
//@ assigns \nothing;
static SVM_INLINE uint8_t popcount8(uint8_t x)
{
    uint8_t count = 0;
    for (; x != 0u; x = (uint8_t)(x & (x - 1u))) {
        count++;
    }
    return count;
}
#else
//@ assigns \nothing;
static SVM_INLINE uint8_t popcount8(uint8_t x)
{
    x = (uint8_t)(x - (uint8_t)((x >> 1) & 0x55u));
    x = (uint8_t)((uint8_t)(x & 0x33u) + (uint8_t)((x >> 2) & 0x33u));
    return (uint8_t)((uint8_t)(x + (uint8_t)(x >> 4)) & 0x0Fu);
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
 * bit at a time. Transitions (fire, weight) test single bytes of the image's masks instead. */
#if FLAT_MASKS && !defined(__AVR__)
/* The minimal profile's flat masks off AVR: a register's width, so that no operation on a mask
 * truncates it to 8 or 16 bits again (an instruction each on ARM). Every mask the step keeps is
 * the image's, zero-extended, or a subset of the events 0 .. E-1. */
typedef unsigned int mask_t;
#elif SVM_MASK_BYTES == 1
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
static SVM_MASK_INLINE mask_t mask_read(uint8_t source, const uint8_t *p, uint8_t m)
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
static SVM_MASK_INLINE mask_t mask_load(const uint8_t *bytes)
{
    mask_t mask = 0;
    uint8_t i;
    for (i = SVM_MASK_BYTES; i != 0u; i--) {
        mask = (mask_t)((mask_t)(mask << 8) | bytes[i - 1u]);
    }
    return mask;
}

static SVM_MASK_INLINE void mask_store(uint8_t *bytes, mask_t mask, uint8_t m)
{
    for (; m != 0u; m--) {
        *bytes++ = (uint8_t)mask;
        mask = (mask_t)(mask >> 8);
    }
}

static SVM_MASK_INLINE mask_t mask_and(mask_t a, mask_t b) { return (mask_t)(a & b); }
static SVM_MASK_INLINE mask_t mask_and_not(mask_t a, mask_t b) { return (mask_t)(a & (mask_t)~b); }
static SVM_MASK_INLINE mask_t mask_or_not(mask_t a, mask_t b) { return (mask_t)(a | (mask_t)~b); }
static SVM_MASK_INLINE uint8_t mask_any(mask_t a) { return a != 0u; }

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
#define MASK_NONE ((mask_t)0u)

/* Cursor over a mask's events: `rest` holds the events not visited yet, shifted down by
 * `base` (a multiple of 8). */
typedef struct cursor {
    mask_t rest;
    uint8_t base;
} cursor_t;

static SVM_MASK_INLINE void cursor_start(cursor_t *c, mask_t mask)
{
    c->rest = mask;
    c->base = 0;
}

static SVM_MASK_INLINE uint8_t cursor_any(const cursor_t *c) { return c->rest != 0u; }
static SVM_MASK_INLINE uint8_t cursor_byte(const cursor_t *c) { return (uint8_t)c->rest; }

/* Leave the current 8 events unvisited. */
static SVM_MASK_INLINE void cursor_skip_byte(cursor_t *c)
{
    c->rest = (mask_t)(c->rest >> 8);
    c->base = (uint8_t)(c->base + 8u);
}

/* Clear bit `bit` of the current byte. */
static SVM_MASK_INLINE void cursor_clear(cursor_t *c, uint8_t bit) { c->rest = (mask_t)(c->rest ^ bit); }

#if !FLAT_MASKS       /* flat masks fire the selected event from the flat loop, with no cursor */
/* A cursor over the one event `e` (no shift of a whole mask). */
static SVM_MASK_INLINE void cursor_single(cursor_t *c, uint8_t e)
{
    c->rest = (mask_t)(1u << (e & 7u));
    c->base = (uint8_t)(e & 0xF8u);
}
#endif

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
#define MASK_NONE mask_low(0u)

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

static SVM_INLINE void cursor_single(cursor_t *c, uint8_t e)
{
    uint8_t i;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        c->rest.b[i] = 0;
    }
    c->at = (uint8_t)(e >> 3);
    c->rest.b[c->at] = (uint8_t)(1u << (e & 7u));
    c->base = (uint8_t)(e & 0xF8u);
}

#endif /* MASK_ARRAY */

#if FLAT_MASKS && !SVM_POPCOUNT_TABLE
/* Flat masks without the table: one bit cleared per set bit over the whole mask, the fewest
 * bytes (the masks counted, an enabled set or a state's events below one, have few bits). */
static uint8_t mask_count(mask_t a)
{
    count_t count = 0;
    for (; a != 0u; a = (mask_t)(a & (mask_t)(a - 1u))) {
        count++;
    }
    return (uint8_t)count;
}
#else
static SVM_MASK_INLINE uint8_t mask_count(mask_t a)
{
    cursor_t c;
    uint8_t count = 0;
    for (cursor_start(&c, a); cursor_any(&c); cursor_skip_byte(&c)) {
        count = (uint8_t)(count + popcount8(cursor_byte(&c)));
    }
    return count;
}
#endif

/* The next event of the cursor (which has one), then visited. */
static SVM_MASK_INLINE uint8_t cursor_next(cursor_t *c)
{
    uint8_t low;
    while ((low = cursor_byte(c)) == 0u) {
        cursor_skip_byte(c);
    }
    low = (uint8_t)(low & (uint8_t)-low);
    cursor_clear(c, low);
    return (uint8_t)(c->base + popcount8((uint8_t)(low - 1u)));    /* the bits below it */
}

/* ---- checksum and validation ------------------------------------------------------------- */

/* CRC-16/MCRF4XX, a byte at a time. The byte-wise form of the reflected CCITT polynomial that
 * avr-libc's _crc_ccitt_update also uses: `d` = the byte xor the low byte of the sum, then
 * crc = (crc >> 8) ^ T[d], T[d] = (e << 8) ^ (e << 3) ^ (e >> 4) with e = d ^ (d << 4) (mod
 * 256). Where flash is not counted in bytes (SVM_CRC_TABLE, off on microcontrollers) T is a
 * 512-byte table, and three more (T2, T3, T4) take four bytes a step; elsewhere T is computed: a few
 * shifts and no branch, on AVR by avr-libc's _crc_ccitt_update (the same step in a few
 * instructions of assembly, smaller than the compiled shifts). */
#ifndef SVM_CRC_TABLE
#if defined(__AVR__) || (defined(__arm__) && !defined(__linux__))
#define SVM_CRC_TABLE 0
#else
#define SVM_CRC_TABLE 1
#endif
#endif

#if SVM_CRC_TABLE && defined(__AVR__)
#error "SVM_CRC_TABLE is for hosts: on AVR its tables would be copied into RAM"
#endif
#if defined(__AVR__)
#include <util/crc16.h>
#endif

#if SVM_CRC_TABLE
#include "swarmvm_crc_tables.h"     /* T, T2, T3, T4: generated by scripts/format_headers.py */
#endif

/* One byte of the sum: the image check's tail and svm_crc16_update (the learned-parameter
 * store's records) share it. */
//@ assigns \nothing;
static SVM_INLINE unsigned crc_byte(unsigned crc, uint8_t byte)
{
#if defined(__AVR__)
    return _crc_ccitt_update((uint16_t)crc, byte);
#elif SVM_CRC_TABLE
    return (crc >> 8) ^ crc_table[(byte ^ crc) & 0xFFu];
#else
    unsigned e = (byte ^ crc) & 0xFFu;
    e = (e ^ (e << 4)) & 0xFFu;
    return (crc >> 8) ^ ((e << 8) & 0xFFFFu) ^ ((e << 3) & 0xFFFFu) ^ (e >> 4);
#endif
}

uint16_t svm_crc16_update(uint16_t crc, uint8_t byte)
{
    return (uint16_t)crc_byte(crc, byte);
}

/* The image checks, from here to svm_validate, are left out of a trusted build: its one image
 * was checked by the compiler that wrote it (swarmvm.h, "Minimal profile"). */
#ifndef SVM_TRUSTED_IMAGE
//@ assigns \nothing;
static SVM_COLD uint16_t crc16(const uint8_t *image, uint8_t source, uint16_t length)
{
    /* A native int (16 bits on AVR) for the sum: no truncation per byte. */
    unsigned crc = SVM_CRC16_INIT;
    uint16_t i = 0;
#if SVM_CRC_TABLE
    //@ loop assigns i, crc;
    for (; (uint32_t)i + 4u <= length; i += 4u) {     /* uint32_t: no wrap where int has 16 bits */
        crc ^= (unsigned)PEEK(source, image + i) | (unsigned)PEEK(source, image + i + 1) << 8;
        crc = crc_table4[crc & 0xFFu] ^ crc_table3[crc >> 8] ^ crc_table2[PEEK(source, image + i + 2)] ^
              crc_table[PEEK(source, image + i + 3)];
    }
    //@ loop assigns i, crc;
    for (; (uint32_t)i + 2u <= length; i += 2u) {
        crc ^= (unsigned)PEEK(source, image + i) | (unsigned)PEEK(source, image + i + 1) << 8;
        crc = crc_table2[crc & 0xFFu] ^ crc_table[crc >> 8];
    }
#endif
    /* Eva: unrolled (an analysis directive, no code), so that the check of a compiled-in image,
     * a constant, is computed exactly (make prove's harnesses: docs/proof.md). */
    /*@ loop unroll 1024;
        loop assigns i, crc; */
    for (; i < length; i++) {
        crc = crc_byte(crc, PEEK(source, image + i));
    }
    return (uint16_t)crc;
}

#endif /* !SVM_TRUSTED_IMAGE */

/* What svm_load needs to know once an image has been accepted: section offsets and header. */
typedef struct layout {
    uint16_t states_at, targets_at, probs_at, names_at;
    uint8_t header[SVM_HEADER_SIZE];
} layout_t;

#ifndef SVM_TRUSTED_IMAGE
/* `count` bytes of an image from `at` into `out` (RAM): the checks below read a record once
 * into locals instead of calling the reader per field. */
/*@ requires \valid(out + (0 .. count - 1)) && \valid_read(image + (at .. at + count - 1)) && at + count <= 65535;
    assigns out[0 .. count - 1]; */
static SVM_COLD void rd_copy(uint8_t *out, const uint8_t *image, uint8_t source, uint16_t at, uint8_t count)
{
    /*@ loop invariant out == \at(out, Pre) + (\at(count, Pre) - count) && at == \at(at, Pre) + (\at(count, Pre) - count);
        loop invariant 0 <= count <= \at(count, Pre);
        loop assigns count, at, out, \at(out, Pre)[0 .. \at(count, Pre) - 1]; */
    for (; count != 0u; count--, at++) {
        *out++ = rd_raw(image, source, at);
    }
}
#endif

#ifndef SVM_TRUSTED_IMAGE
/* The little-endian u16 at `p` in RAM (the header's fields, read by validation only). */
/*@ requires \valid_read(p + (0 .. 1));
    assigns \nothing; */
static SVM_INLINE uint16_t le16(const uint8_t *p)
{
    return (uint16_t)(p[0] | ((unsigned)p[1] << 8));
}

/* Whether byte `last` of an event mask (its last byte) has a bit at or above event `e` (in the
 * padding): an event the image does not have. */
//@ assigns \nothing;
static SVM_INLINE uint8_t beyond_events(uint8_t last, uint8_t e)
{
    uint8_t used = (uint8_t)(e & 7u);
    return used != 0u && (uint8_t)(last >> used) != 0u;
}

/* Whether the event mask of `m` bytes at `at` has a bit beyond the image's `e` events. */
/*@ requires 1 <= m && at + m - 1 <= 65535 && \valid_read(image + at + m - 1);
    assigns \nothing; */
static SVM_COLD uint8_t mask_beyond(const uint8_t *image, uint8_t source, uint16_t at, uint8_t m, uint8_t e)
{
    return beyond_events(rd_raw(image, source, (uint16_t)(at + (uint8_t)(m - 1u))), e);
}

/* Every index the step follows must stay inside the image, every event mask inside the image's
 * events: check them once here, with what else the compiler always writes (docs/image-format.md):
 * each supervisor starts in its state 0, a state has transitions only on its supervisor's
 * events, and each state's successors follow the previous state's, the last ending at T (no
 * target is read by two states or by none). Supervisor and state records are walked in order
 * (the states of supervisor s follow those of s - 1), so no record offset is multiplied out. */
/*@ lemma one_record_fits: \forall integer r, m; 1 <= r && 0 <= m ==> m + 2 <= r * (m + 2);
    lemma one_supervisor_fits: \forall integer r, m; 1 <= r && 0 <= m ==> m + 6 <= r * (m + 6); */

/*@ requires validated: \valid_read(lay);
    requires validated: 1 <= lay->header[SVM_AT_NUM_EVENTS] && lay->header[SVM_AT_MASK_BYTES] == (lay->header[SVM_AT_NUM_EVENTS] + 7) / 8;
    requires validated: 1 <= lay->header[SVM_AT_STATE_WIDTH] <= 2;
    requires validated: lay->states_at == SUPS_AT(lay->header[SVM_AT_MASK_BYTES])
                               + lay->header[SVM_AT_NUM_SUPERVISORS] * SUP_SIZE(lay->header[SVM_AT_MASK_BYTES]);
    requires validated: lay->targets_at == lay->states_at + total_states * STATE_SIZE(lay->header[SVM_AT_MASK_BYTES]);
    requires validated: \valid_read(image + (0 .. lay->targets_at - 1 + (lay->header[SVM_AT_STATE_WIDTH] == 1 ? 1 : 2) * total_trans));
    assigns \nothing;
    ensures \result == SVM_OK || \result == SVM_ERR_LAYOUT; */
static SVM_INLINE int check_indices(const uint8_t *image, uint8_t source, const layout_t *lay, uint16_t total_states,
                                    uint16_t total_trans)
{
    const uint8_t *h = lay->header;
    uint8_t m = h[SVM_AT_MASK_BYTES], width = h[SVM_AT_STATE_WIDTH], n = h[SVM_AT_NUM_SUPERVISORS];
    uint8_t e = h[SVM_AT_NUM_EVENTS], s, record[6];
    int accepted;
    uint16_t expected_first = 0, expected_succ = 0, alphabet = (uint16_t)SUPS_AT(m);
    const uint8_t *st = image + lay->states_at, *targets = image + lay->targets_at;
    if (mask_beyond(image, source, CONTROLLABLE_AT, m, e) || mask_beyond(image, source, (uint16_t)PUBLIC_AT(m), m, e)) {
        return SVM_ERR_LAYOUT;
    }
    /* `rest`, a ghost (proof-only) count of the state records not walked yet, at least the states
     * left: the provers bound a record's offset by one product, rest * STATE_SIZE(m). */
    //@ ghost int rest = total_states;
    /*@ loop invariant sups: 0 <= s <= n && alphabet == SUPS_AT(m) + s * SUP_SIZE(m);
        loop invariant sups_rest: lay->states_at - alphabet == (n - s) * SUP_SIZE(m);
        loop invariant walked: expected_first <= total_states && expected_succ <= total_trans;
        loop invariant rest_bound: rest >= total_states - expected_first;
        loop invariant st_in: \base_addr(st) == \base_addr(image) && lay->states_at <= st - image;
        loop invariant st_rest: lay->targets_at - (st - image) == rest * STATE_SIZE(m);
        loop assigns s, alphabet, expected_first, expected_succ, st, rest, record[0 .. 5]; */
    for (s = 0; s < n; s++, alphabet = (uint16_t)(alphabet + SUP_SIZE(m))) {
        uint16_t first, count, q;
        //@ assert one_more_supervisor: alphabet + SUP_SIZE(m) <= lay->states_at;
        rd_copy(record, image, source, (uint16_t)(alphabet + m), 6u);    /* first, count, initial */
        first = le16(record);
        count = le16(record + 2);
        if (first != expected_first || count == 0 || le16(record + 4) != 0u || count > total_states - first ||
            mask_beyond(image, source, alphabet, m, e)) {
            return SVM_ERR_LAYOUT;
        }
        //@ assert first + count <= total_states;
        /*@ loop invariant q: 0 <= q <= count && expected_succ <= total_trans;
            loop invariant rest_bound: rest >= total_states - first - q;
            loop invariant st_in: \base_addr(st) == \base_addr(image) && lay->states_at <= st - image;
            loop invariant st_rest: lay->targets_at - (st - image) == rest * STATE_SIZE(m);
            loop assigns q, st, expected_succ, rest; */
        for (q = 0; q < count; q++, st += STATE_SIZE(m)) {
            uint16_t defined = 0, succ, k;
            const uint8_t *target;
            uint8_t i, byte = 0, foreign = 0;
            //@ assert one_more: rest >= 1;
            /*@ loop invariant 0 <= i <= m;
                loop assigns i, byte, foreign, defined; */
            for (i = 0; i < m; i++) {
                byte = PEEK(source, st + i);
                foreign |= (uint8_t)(byte & (uint8_t)~PEEK(source, image + alphabet + i));
                defined = (uint16_t)(defined + popcount8(byte));
            }
            succ = (uint16_t)(PEEK(source, st + m) + 256u * PEEK(source, st + m + 1));     /* a sum: WP bounds it */
            if (foreign != 0u || beyond_events(byte, e) || succ != expected_succ || defined > total_trans - succ) {
                return SVM_ERR_LAYOUT;
            }
            expected_succ = (uint16_t)(succ + defined);
            target = targets + succ;
            if (width != 1u) {
                target += succ;     /* two bytes a target (the width is 1 or 2: validate) */
            }
            /*@ loop invariant 0 <= k <= defined;
                loop invariant target: \base_addr(target) == \base_addr(image) && target - targets == (width == 1 ? 1 : 2) * (succ + k);
                loop assigns k, target; */
            for (k = 0; k < defined; k++, target += width) {
                unsigned local = PEEK(source, target);
                if (width != 1u) {
                    local |= (unsigned)PEEK(source, target + 1) << 8;
                }
                if (local >= count) {
                    return SVM_ERR_LAYOUT;
                }
            }
            //@ ghost rest = rest - 1;
        }
        expected_first = (uint16_t)(first + count);
    }
    /* Accepted when the records account for the header's states and transitions. Eva keeps
     * that path apart from the refusals (split), so that load's test of the result tells it what
     * an accepted image's layout holds. */
    accepted = expected_first == total_states && expected_succ == total_trans;
    //@ split accepted;
    return accepted ? SVM_OK : SVM_ERR_LAYOUT;
}

/* Whether `c` may be part of an event name: letters, digits and '_' (the input languages' rule). */
//@ assigns \nothing;
static uint8_t name_char(uint8_t c)
{
    return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

#if SVM_WITH_NAMES
/* Whether the name whose length byte is at `pos` equals one of the names from `at` (the section's
 * start) up to it, which validate checked earlier: they follow each other up to `pos`. The
 * compiler writes each event's name once; a name given twice would make binding by name
 * ambiguous. Only in builds that read names (SVM_WITH_NAMES): the Kilobot's compiled-in build
 * never reads them, and its VM core's flash budget cannot spare the check (docs/image-format.md
 * gives its size). The walk goes by position (`at < pos`), so each length byte it reads is
 * evidently inside the names already checked. */
//@ assigns \nothing;
static SVM_COLD uint8_t name_repeats(const uint8_t *image, uint8_t source, uint16_t at, uint16_t pos)
{
    const uint8_t *name = image + pos;
    uint8_t n = PEEK(source, name);
    //@ loop assigns at;
    while (at < pos) {
        const uint8_t *first = image + at;
        uint8_t k = PEEK(source, first);
        at = (uint16_t)(at + 1u + k);
        if (k == n) {
            //@ loop assigns k;
            while (k != 0u && PEEK(source, first + k) == PEEK(source, name + k)) {
                k--;
            }
            if (k == 0u) {
                return 1;
            }
        }
    }
    return 0;
}
#endif

/* Past every image: a section end beyond the checksum (lengths are at most 65535). */
#define PAST_END 0xFFFFu

/* `pos` + `count` * `size`, or PAST_END when that passes `end` (<= 65533): section offsets stay
 * 16-bit and a corrupt header never makes them wrap around (PAST_END stays PAST_END). */
/*@ assigns \nothing;
    ensures \result == (count * size + pos > end ? PAST_END : count * size + pos); */
static SVM_COLD uint16_t section_end(uint16_t pos, uint16_t count, uint8_t size, uint16_t end)
{
    uint32_t to = (uint32_t)count * size + pos;
    return to > end ? PAST_END : (uint16_t)to;
}

/* Past the sections that follow the transitions' (and their probabilities) in an image: the names
 * (each of letters, digits and '_', none given twice), the order (a permutation of the events,
 * then the states' order) and the source, those the header's flags say it has; PAST_END when one
 * does not fit before `end` or does not read as its section. A function of its own so that
 * validate's contract (WP, docs/proof.md) needs of it only that it ends at or after `pos`. */
/*@ assigns lay->names_at;
    ensures \result >= pos; */
static uint16_t trailer_end(const uint8_t *image, uint8_t source, layout_t *lay, uint16_t pos, uint16_t end)
{
    const uint8_t *h = lay->header;
    uint8_t flags = h[SVM_AT_FLAGS], e = h[SVM_AT_NUM_EVENTS], i;
    uint16_t states = le16(h + SVM_AT_NUM_STATES);
    if (flags & SVM_FLAG_NAMES) {
        lay->names_at = pos;
        /*@ loop invariant \at(pos, Pre) <= pos;
            loop assigns i, pos; */
        for (i = 0; i < e; i++) {
            uint16_t name_end;
            if (pos >= end || (name_end = section_end((uint16_t)(pos + 1u), rd_raw(image, source, pos), 1u, end)) ==
                                  PAST_END) {
                return PAST_END;
            }
#if SVM_WITH_NAMES
            if (name_repeats(image, source, lay->names_at, pos)) {
                return PAST_END;
            }
#endif
            /*@ loop invariant \at(pos, Pre) <= pos <= name_end <= end;
                loop assigns pos; */
            for (pos++; pos < name_end; pos++) {
                if (!name_char(rd_raw(image, source, pos))) {
                    return PAST_END;
                }
            }
        }
    }
    if (flags & SVM_FLAG_ORDER) {     /* read by the compatibility layers only: bounds checked */
        uint16_t order = pos, order_end = section_end(pos, e, 1u, end), k;
        if (order_end == PAST_END || section_end(order_end, states, 2u, end) == PAST_END) {
            return PAST_END;
        }
        /*@ loop invariant \at(pos, Pre) <= pos <= order_end;
            loop assigns pos, k; */
        for (; pos < order_end; pos++) {      /* each event index below e, once: a permutation */
            uint8_t listed = rd_raw(image, source, pos);
            if (listed >= e) {
                return PAST_END;
            }
            //@ loop assigns k;
            for (k = order; k < pos; k++) {
                if (PEEK(source, image + k) == listed) {
                    return PAST_END;
                }
            }
        }
        pos = section_end(pos, states, 2u, end);
    }
    if (flags & SVM_FLAG_SOURCE) {    /* the compatibility layers' only: skipped, bounds checked */
        pos = section_end(pos, (uint16_t)(32u + 2u * h[SVM_AT_NUM_SUPERVISORS]), 1u, end);
        /*@ loop invariant \at(pos, Pre) <= pos;
            loop assigns i, pos; */
        for (i = 0; i < e && pos != PAST_END; i++) {
            pos = pos >= end ? PAST_END : section_end((uint16_t)(pos + 1u), rd_raw(image, source, pos), 1u, end);
        }
    }
    return pos;
}

/*@ requires image == \null || \valid_read(image + (0 .. length - 1));
    requires \valid(lay);
    assigns *lay; */
static SVM_COLD int validate(const uint8_t *image, uint8_t source, uint16_t length, layout_t *lay)
{
    /* The header is copied into lay->header here, before anything reads it. */
    uint8_t *h = lay->header, flags, e, m;  // cppcheck-suppress ctuuninitvar
    uint16_t states, trans, end, pos;
    if (image == 0 || length < SVM_MIN_IMAGE_SIZE) {
        return SVM_ERR_LENGTH;
    }
    rd_copy(h, image, source, 0u, SVM_HEADER_SIZE);
    if (le16(h + SVM_AT_LENGTH) != length) {
        return SVM_ERR_LENGTH;
    }
    if (le16(h + SVM_AT_MAGIC) != (uint16_t)SVM_MAGIC || le16(h + SVM_AT_MAGIC + 2u) != (uint16_t)(SVM_MAGIC >> 16)) {
        return SVM_ERR_MAGIC;
    }
    if (h[SVM_AT_VERSION] != SVM_FORMAT_VERSION) {
        return SVM_ERR_VERSION;
    }
    end = (uint16_t)(length - SVM_CRC_SIZE);
    if (crc16(image, source, end) != rd16_raw(image, source, end)) {
        return SVM_ERR_CRC;
    }
    flags = h[SVM_AT_FLAGS];
    e = h[SVM_AT_NUM_EVENTS];
    states = le16(h + SVM_AT_NUM_STATES);
    trans = le16(h + SVM_AT_NUM_TRANSITIONS);
    m = h[SVM_AT_MASK_BYTES];
    /* (The order section comes only with the names: the compiler writes it with them.) */
    if (e == 0 || h[SVM_AT_NUM_SUPERVISORS] == 0 || h[SVM_AT_STATE_WIDTH] == 0 || h[SVM_AT_STATE_WIDTH] > 2u ||
        m != (uint8_t)((e + 7u) / 8u) || (flags & (uint8_t)~SVM_KNOWN_FLAGS) != 0u ||
        (flags & (SVM_FLAG_ORDER | SVM_FLAG_NAMES)) == SVM_FLAG_ORDER ||
        (flags & (SVM_FLAG_SOURCE | SVM_FLAG_ORDER)) == SVM_FLAG_SOURCE) {
        return SVM_ERR_LAYOUT;
    }
#if SVM_MASK_EXACT
    if (h[SVM_AT_MASK_BYTES] != SVM_MASK_BYTES) {     /* the header's byte, as the limits below */
        return SVM_ERR_LIMITS;
    }
#endif
    lay->states_at = pos = section_end((uint16_t)SUPS_AT(m), h[SVM_AT_NUM_SUPERVISORS], (uint8_t)SUP_SIZE(m), end);
    lay->targets_at = pos = section_end(pos, states, (uint8_t)STATE_SIZE(m), end);
    pos = section_end(pos, trans, h[SVM_AT_STATE_WIDTH], end);
    lay->probs_at = 0;
    if (flags & SVM_FLAG_PROBS) {
        lay->probs_at = pos;
        pos = section_end(pos, trans, 2u, end);
    }
    lay->names_at = 0;
    if (pos > end) {
        return SVM_ERR_LAYOUT;
    }
    if (trailer_end(image, source, lay, pos, end) != end) {
        return SVM_ERR_LAYOUT;
    }
    /* (Tested on the header's bytes, which install copies: Eva then bounds the VM's counts. Each
     * test is left out when the limit is the field's range: it could not fail.) */
#if SVM_MAX_EVENTS < SVM_FORMAT_MAX_EVENTS
    if (h[SVM_AT_NUM_EVENTS] > SVM_MAX_EVENTS) {
        return SVM_ERR_LIMITS;
    }
#endif
#if SVM_MAX_SUPERVISORS < SVM_FORMAT_MAX_SUPERVISORS
    if (h[SVM_AT_NUM_SUPERVISORS] > SVM_MAX_SUPERVISORS) {
        return SVM_ERR_LIMITS;
    }
#endif
#if SVM_MAX_STATES < SVM_FORMAT_MAX_STATES
    if (states > SVM_MAX_STATES) {
        return SVM_ERR_LIMITS;
    }
#endif
    return check_indices(image, source, lay, states, trans);
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

SVM_COLD int svm_validate(const uint8_t *image, uint16_t length, uint8_t source)
{
    layout_t lay;
    return readable(source) ? validate(image, source, length, &lay) : SVM_ERR_SOURCE;
}

#endif /* !SVM_TRUSTED_IMAGE */

/* ---- life cycle ---------------------------------------------------------------------------- */

SVM_COLD void svm_init(svm_vm_t *vm)
{
    uint8_t *raw = (uint8_t *)vm;
    uint16_t i;
    /* Eva: unrolled, so that it sees every byte written (a VM on the stack starts unknown). */
    //@ loop unroll sizeof(svm_vm_t);
    for (i = 0; i < sizeof *vm; i++) {
        raw[i] = 0;
    }
    vm->image = 0;
#if SVM_WITH_BINDINGS
    vm->bindings = 0;
#endif
    vm->dispatch = 0;
#if SVM_WITH_LEARNED
    vm->chooser = 0;
    vm->chooser_ctx = 0;
#endif
#if SVM_WITH_VIOLATIONS
    vm->on_violation = 0;
#endif
#if SVM_WITH_FIRST
    vm->priority = 0;
    vm->priority_by_name = 0;
#endif
    vm->seed = SVM_DEFAULT_SEED;
    vm->rng = SVM_DEFAULT_SEED;
}

SVM_COLD void svm_reset(svm_vm_t *vm)
{
    /* Every accepted image has masks of SVM_MASK_BYTES in an exact build, and starts each
     * supervisor in its local state 0 (the load's checks, or the compiler for a trusted image):
     * its global initial state is its first. */
    uint8_t s, m = SVM_MASK_EXACT ? (uint8_t)SVM_MASK_BYTES : VM_MASK_BYTES(vm);
#ifdef SVM_TRUSTED_IMAGE
    /* The profile's one image, whose counts are the build's: read at its own address, loaded or
     * not (before a load the states are not read: every reader checks that an image is loaded). */
    const uint8_t *record = (const uint8_t *)SVM_TRUSTED_IMAGE + SUPS_AT(m) + m;
    for (s = 0; s < SVM_MAX_SUPERVISORS; s++, record += SUP_SIZE(m)) {
#else
    const uint8_t *record = vm->image + SUPS_AT(m) + m;    /* first state, count, initial */
    for (s = 0; s < vm->num_supervisors; s++, record += SUP_SIZE(m)) {
#endif
        vm->state[s] = (svm_state_t)peek16(VM_SOURCE(vm), record);
    }
    for (s = 0; s < SVM_MASK_BYTES; s++) {
        vm->previous[s] = 0;
    }
#if SVM_WITH_VIOLATIONS
    vm->violations = 0;
#endif
    vm->rng = vm->seed ? vm->seed : SVM_ZERO_SEED;
}

#if SVM_WITH_NAMES
/* Offset of the event's name record (length byte, then the name) in an image. */
static SVM_COLD uint16_t name_at(const uint8_t *image, uint8_t source, uint16_t names_at, uint8_t event)
{
    uint16_t pos = names_at;
    uint8_t i;
    for (i = 0; i < event; i++) {
        pos = (uint16_t)(pos + 1u + rd_raw(image, source, pos));
    }
    return pos;
}

#if REBIND_BY_NAME
/* Index, in a new image (validated, not yet loaded), of the old image's event of the same
 * name; -1 if it has none. Either image may be in flash, RAM or EEPROM. */
static SVM_COLD int find_in_new(const svm_vm_t *vm, const uint8_t *image, uint8_t source,
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

#if SVM_WITH_BINDINGS
static uint8_t is_bound(const svm_binding_t *b)
{
    return b->action != 0 || b->check != 0 || b->data != 0;
}

/* Swap: move each runtime binding from its old event index to the index its name has in the
 * new image, in place. The map is injective (names are unique), so carrying a binding to its
 * new slot, picking up the binding that slot held and carrying that on, places every binding
 * once, whether its moves form a chain or a cycle. */
static SVM_COLD int rebind_by_name(svm_vm_t *vm, const uint8_t *image, uint8_t source, const layout_t *lay)
{
    uint8_t map[SVM_MAX_EVENTS] = {0};     /* zeroed only for gcc's flow analysis: entries past */
    uint8_t moved[SVM_MASK_BYTES];          /* `limit` are never read (-Wmaybe-uninitialized at */
    uint8_t e, cap = vm->bindings_cap;      /* SVM_MAX_EVENTS=1 on arm-none-eabi-gcc)            */
    uint8_t limit = VM_EVENTS(vm) < cap ? VM_EVENTS(vm) : cap;
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
#endif /* SVM_WITH_BINDINGS */

#if SVM_WITH_FIRST
/* Swap: the priority list of svm_bind_priority follows its events' names into the new image;
 * with `write` 0 only checks that every name is there, so that a refusal changes nothing. */
static SVM_COLD int rebind_priority(svm_vm_t *vm, const uint8_t *image, uint8_t source, const layout_t *lay,
                           uint8_t write)
{
    uint8_t k;
    for (k = 0; k < vm->priority_count; k++) {
        int to = -1;
        if (vm->priority_by_name[k] < VM_EVENTS(vm)) {
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
#endif /* SVM_WITH_FIRST */
#endif /* REBIND_BY_NAME */
#endif /* SVM_WITH_NAMES */

#ifdef SVM_TRUSTED_IMAGE
/* Minimal profile: the one image is the generator's constant, which the compiler checked when it
 * wrote it, so nothing of it is checked again but that its counts are the build's limits (they
 * size the VM's arrays and are the step's constants) and that it is that image: a pointer to any
 * other bytes is refused, so the profile cannot run an image that did not come from the
 * compiler. Its sections follow from the header (docs/image-format.md). */
SVM_COLD int svm_load_P(svm_vm_t *vm, const uint8_t *image, uint16_t length)
{
    /* The header's counts, num_events, num_supervisors and num_states (bytes 6-9, little-endian),
     * as the build's limits give them; with them the image's mask width (ceil(E / 8)) and, for
     * 256 states or fewer, its state width (1) are the compiler's, and the step's constants. */
    uint32_t counts;
    (void)length;
    if (image != SVM_TRUSTED_IMAGE) {
        return SVM_ERR_SOURCE;
    }
#if defined(__AVR__)
    counts = pgm_read_dword(image + SVM_AT_NUM_EVENTS);
#else
    counts = (uint32_t)image[SVM_AT_NUM_EVENTS] | ((uint32_t)image[SVM_AT_NUM_EVENTS + 1] << 8) |
             ((uint32_t)image[SVM_AT_NUM_EVENTS + 2] << 16) | ((uint32_t)image[SVM_AT_NUM_EVENTS + 3] << 24);
#endif
    if (counts != ((uint32_t)SVM_MAX_EVENTS | ((uint32_t)SVM_MAX_SUPERVISORS << 8) | ((uint32_t)SVM_MAX_STATES << 16))) {
        return SVM_ERR_LIMITS;
    }
#if !SVM_WITH_PUBLIC
    /* A build without the public pass runs only an image without public uncontrollable events
     * (the only ones the pass polls and applies first; a public controllable event is chosen
     * as any other). */
    if (mask_any(mask_and_not(mask_read(VM_SOURCE(vm), image + PUBLIC_AT(SVM_MASK_BYTES), SVM_MASK_BYTES),
                              mask_read(VM_SOURCE(vm), image + CONTROLLABLE_AT, SVM_MASK_BYTES)))) {
        return SVM_ERR_LIMITS;
    }
#endif
    /* The counts, mask width and source are the build's (LOADED_*, VM_SOURCE). */
    vm->image = image;
#if SVM_MAX_STATES > 256 || SVM_WITH_WEIGHTED || SVM_WITH_LEARNED || SVM_WITH_NAMES
    vm->width = READ(image, VM_SOURCE(vm), SVM_AT_STATE_WIDTH);
#endif
#if SVM_WITH_WEIGHTED || SVM_WITH_LEARNED || SVM_WITH_NAMES
    {   /* the sections after the targets, read only by the features that use them */
        uint8_t flags = rd_raw(image, VM_SOURCE(vm), SVM_AT_FLAGS);
        uint16_t trans = rd16_raw(image, VM_SOURCE(vm), SVM_AT_NUM_TRANSITIONS);
        uint16_t pos = (uint16_t)(TRUSTED_TARGETS_AT + trans * vm->width);
#if SVM_WITH_WEIGHTED || SVM_WITH_LEARNED
        vm->probs_at = (flags & SVM_FLAG_PROBS) ? pos : 0u;
#endif
        if (flags & SVM_FLAG_PROBS) {
            pos = (uint16_t)(pos + 2u * trans);
        }
#if SVM_WITH_NAMES
        vm->names_at = (flags & SVM_FLAG_NAMES) ? pos : 0u;
#endif
        (void)pos;
    }
#endif
    svm_reset(vm);
    return SVM_OK;
}
#else /* !SVM_TRUSTED_IMAGE */
/* Run an accepted image from its initial states (both loaders' last step; inlined into them,
 * a call of its own cost flash). */
static SVM_INLINE void install(svm_vm_t *vm, const uint8_t *image, uint8_t source, const layout_t *lay)
{
    vm->image = image;
    vm->source = source;
    vm->states_at = lay->states_at;
    vm->targets_at = lay->targets_at;
#if SVM_WITH_WEIGHTED || SVM_WITH_LEARNED
    vm->probs_at = lay->probs_at;
#endif
#if SVM_WITH_NAMES
    vm->names_at = lay->names_at;
#endif
    vm->num_events = lay->header[SVM_AT_NUM_EVENTS];
    vm->num_supervisors = lay->header[SVM_AT_NUM_SUPERVISORS];
    vm->width = lay->header[SVM_AT_STATE_WIDTH];
    /* The header's mask width as validate checked it: ceil(E / 8), the build's in an exact build. */
    vm->mask_bytes = (uint8_t)(SVM_MASK_EXACT ? SVM_MASK_BYTES : (vm->num_events + 7u) / 8u);
    svm_reset(vm);
}

static SVM_COLD int load(svm_vm_t *vm, const uint8_t *image, uint16_t length, uint8_t source)
{
    layout_t lay;
#if REBIND_BY_NAME
    uint8_t rebind = vm->image != 0 && vm->names_at != 0;
#endif
    int result = validate(image, source, length, &lay);
    if (result != SVM_OK) {
        return result;
    }
#if SVM_WITH_NAMES && SVM_WITH_FIRST
    if (rebind && vm->priority_by_name != 0 && (result = rebind_priority(vm, image, source, &lay, 0)) != SVM_OK) {
        return result;
    }
#endif
#if SVM_WITH_NAMES && SVM_WITH_BINDINGS
    if (rebind && vm->bindings != 0 && (result = rebind_by_name(vm, image, source, &lay)) != SVM_OK) {
        return result;
    }
#endif
#if SVM_WITH_NAMES && SVM_WITH_FIRST
    if (rebind && vm->priority_by_name != 0) {
        (void)rebind_priority(vm, image, source, &lay, 1);
    }
#endif
    install(vm, image, source, &lay);
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
#endif /* SVM_TRUSTED_IMAGE */

void svm_set_options(svm_vm_t *vm, uint8_t options, uint32_t seed)
{
    vm->options = options;
    vm->seed = seed;
}

/* ---- callbacks ----------------------------------------------------------------------------- */

#if SVM_WITH_BINDINGS
SVM_COLD void svm_set_bindings(svm_vm_t *vm, svm_binding_t *table, uint8_t cap)
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

SVM_COLD int svm_bind(svm_vm_t *vm, uint8_t event, svm_action_fn action, svm_check_fn check, void *data)
{
    if (vm->bindings == 0) {
        return SVM_ERR_NO_BINDINGS;
    }
    if (vm->image == 0 || event >= VM_EVENTS(vm) || event >= vm->bindings_cap ||
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
#endif

void svm_set_dispatch(svm_vm_t *vm, svm_dispatch_fn dispatch)
{
    vm->dispatch = dispatch;
}

#if SVM_WITH_LEARNED
void svm_set_chooser(svm_vm_t *vm, svm_chooser_fn chooser, void *ctx)
{
    vm->chooser = chooser;
    vm->chooser_ctx = ctx;
}
#endif

#if SVM_WITH_FIRST
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
#endif

#if SVM_WITH_VIOLATIONS
void svm_set_on_violation(svm_vm_t *vm, svm_violation_fn hook)
{
    vm->on_violation = hook;
}
#endif

static void act(svm_vm_t *vm, uint8_t event)
{
#if SVM_WITH_BINDINGS
    if (vm->bindings != 0 && event < vm->bindings_cap && vm->bindings[event].action != 0) {
        vm->bindings[event].action(vm->bindings[event].data);
        return;
    }
#endif
    if (vm->dispatch != 0) {
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

#if SVM_WITH_VIOLATIONS
static void violate(svm_vm_t *vm, uint8_t event, uint8_t s)
{
    if (vm->violations != SVM_MAX_VIOLATIONS) {
        vm->violations++;
    }
    if (vm->on_violation != 0) {
        vm->on_violation(vm, event, s);
    }
}
#endif

/* Docs/semantics.md step 3: move every supervisor that has the event, count violations, then
 * run the event's action. Supervisor records are walked in order, without multiplications.
 * `m` is the mask width: see step_m for why it is a parameter. */
#if FLAT_MASKS
/* Flat masks: the event is its bit in a whole mask, `bit`; the alphabet and the state's `defined`
 * mask are read whole (one or two bytes), and the transition's rank is the count of the state's
 * events below it, with no walk over the mask's bytes. */
static SVM_FIRE void fire(svm_vm_t *vm, uint8_t event, mask_t bit, uint8_t m)
{
    const uint8_t *img = VM_IMAGE(vm);
    const uint8_t *states = img + VM_STATES_AT(vm), *targets = img + VM_TARGETS_AT(vm);
    const uint8_t *sup = img + SUPS_AT(m);
    svm_state_t *state = vm->state;
    uint8_t src = VM_SOURCE(vm), narrow = VM_NARROW(vm);
    count_t n = VM_SUPERVISORS(vm), s;
    for (s = 0; s < n; s++, sup += SUP_SIZE(m)) {
        const uint8_t *st;
        mask_t defined;
        uint16_t t, local;
        if (!mask_any(mask_and(mask_read(src, sup, m), bit))) {
            continue;
        }
        st = states + (uint16_t)state[s] * STATE_SIZE(m);
        defined = mask_read(src, st, m);
        if (!mask_any(mask_and(defined, bit))) {
#if SVM_WITH_VIOLATIONS
            violate(vm, event, s);
#endif
            continue;
        }
        t = (uint16_t)(peek16(src, st + m) + mask_count(mask_and(defined, (mask_t)(bit - 1u))));
        local = narrow ? PEEK(src, targets + t) : peek16(src, targets + 2u * t);
        state[s] = (svm_state_t)(peek16(src, sup + m) + local);
    }
    act(vm, event);
}
#else
static SVM_FIRE void fire(svm_vm_t *vm, uint8_t event, uint8_t byte, uint8_t bit, uint8_t m)
{
    const uint8_t *img = VM_IMAGE(vm);
    const uint8_t *states = img + VM_STATES_AT(vm), *targets = img + VM_TARGETS_AT(vm);
    const uint8_t *sup = img + SUPS_AT(m);
    svm_state_t *state = vm->state;
    uint8_t src = VM_SOURCE(vm), n = VM_SUPERVISORS(vm), narrow = VM_NARROW(vm), s;
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
#if SVM_WITH_VIOLATIONS
            violate(vm, event, s);
#endif
            continue;
        }
        t = successor(src, st, m, defined, byte, bit);
        local = narrow ? PEEK(src, targets + t) : peek16(src, targets + 2u * t);
        state[s] = (svm_state_t)(peek16(src, sup + m) + local);
    }
    act(vm, event);
}
#endif

/* The enabled controllable events among `candidates` (docs/semantics.md step 5). */
static SVM_MASK_INLINE mask_t enabled_set(const svm_vm_t *vm, mask_t candidates, uint8_t m)
{
    const uint8_t *img = VM_IMAGE(vm), *sup = img + SUPS_AT(m), *states = img + VM_STATES_AT(vm);
    const svm_state_t *state = vm->state;
    uint8_t src = VM_SOURCE(vm), s;
    for (s = VM_SUPERVISORS(vm); s != 0u; s--, sup += SUP_SIZE(m)) {
        const uint8_t *st = states + (uint16_t)*state++ * STATE_SIZE(m);
        candidates = mask_and(candidates, mask_or_not(mask_read(src, st, m), mask_read(src, sup, m)));
    }
    return candidates;
}

/* The events 0 .. E-1 of the loaded image. */
static SVM_INLINE mask_t valid_events(const svm_vm_t *vm)
{
    return VM_EVENTS(vm) == SVM_MAX_EVENTS ? MASK_LOW_MAX : mask_low(VM_EVENTS(vm));
}

static SVM_INLINE mask_t enabled_m(const svm_vm_t *vm, uint8_t m)
{
    mask_t controllable = mask_read(VM_SOURCE(vm), VM_IMAGE(vm) + CONTROLLABLE_AT, m);
    return enabled_set(vm, mask_and(controllable, valid_events(vm)), m);
}

uint8_t svm_enabled(const svm_vm_t *vm, uint8_t *enabled)
{
    mask_t mask;
    if (vm->image == 0) {
        return 0;
    }
#if !SVM_MASK_EXACT
    if (VM_MASK_BYTES(vm) != SVM_MASK_BYTES) {
        mask = enabled_m(vm, MASK_WIDTH(VM_MASK_BYTES(vm)));
    } else
#endif
    {
        mask = enabled_m(vm, SVM_MASK_BYTES);
    }
    mask_store(enabled, mask, VM_MASK_BYTES(vm));
    return mask_count(mask);
}

#if SVM_WITH_WEIGHTED || SVM_WITH_LEARNED
uint32_t svm_weight(const svm_vm_t *vm, uint8_t event)
{
    const uint8_t *img = vm->image, *sup, *states, *probs;
    uint32_t weight = SVM_Q15_ONE;
    uint8_t src = VM_SOURCE(vm), m = VM_MASK_BYTES(vm), byte = (uint8_t)(event >> 3), bit = (uint8_t)(1u << (event & 7u)), s;
    if (vm->probs_at == 0) {
        return weight;
    }
    sup = img + SUPS_AT(m);
    states = img + VM_STATES_AT(vm);
    probs = img + vm->probs_at;
    for (s = 0; s < VM_SUPERVISORS(vm); s++, sup += SUP_SIZE(m)) {
        const uint8_t *st = states + (uint16_t)vm->state[s] * STATE_SIZE(m);
        uint8_t defined = PEEK(src, st + byte);
        if ((PEEK(src, sup + byte) & bit) && (defined & bit)) {
            weight = (weight * peek16(src, probs + 2u * successor(src, st, m, defined, byte, bit))) >> 15;
        }
    }
    return weight;
}
#endif

SVM_COLD uint8_t svm_mask_nth(const uint8_t *mask, uint8_t bytes, uint8_t n)
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

#if FLAT_MASKS && defined(__GNUC__) && !defined(__AVR__)
/* The `n`-th event (from 0) of `mask`, which has more than n: its n lowest events cleared, the
 * index of the lowest left. Where counting trailing zeros is an instruction or two (the
 * Cortex-M4's rbit and clz) this is smaller than a walk over the bits and takes no more
 * instructions; avr-gcc's __builtin_ctz is a library call, so AVR walks. */
static uint8_t nth_event(mask_t mask, count_t n)
{
    for (; n != 0u; n--) {
        mask = (mask_t)(mask & (mask_t)(mask - 1u));
    }
    return (uint8_t)__builtin_ctz(mask);
}
#elif FLAT_MASKS
/* The `n`-th event (from 0) of `mask`, which has more than n. */
static uint8_t nth_event(mask_t mask, count_t n)
{
    count_t event;
    for (event = 0;; mask = (mask_t)(mask >> 1), event++) {
        if ((mask & 1u) && n-- == 0u) {
            return (uint8_t)event;
        }
    }
}
#else
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
#endif

/* floor(((r >> 16) * count) / 65536) (docs/semantics.md, policy uniform) with 8 x 8-bit
 * products: with h = r >> 16 = 256 hi + lo, h * count / 65536 = (hi * count + lo * count / 256)
 * / 256, each division a floor. */
static uint8_t uniform_index(uint32_t r, uint8_t count)
{
#if defined(SVM_TRUSTED_IMAGE) && !defined(__AVR__)
    /* The same floor with one 32-bit product, where that is one instruction (the minimal
     * profile off AVR; other builds keep their form, so their code stays as it was). */
    return (uint8_t)(((r >> 16) * (uint32_t)count) >> 16);
#else
    uint8_t hi = (uint8_t)(r >> 24), lo = (uint8_t)(r >> 16);
    uint16_t low_part = (uint16_t)((uint16_t)lo * count) >> 8;
    return (uint8_t)(((uint16_t)((uint16_t)hi * count) + low_part) >> 8);
#endif
}

#if SVM_WITH_FIRST || SVM_WITH_LEARNED
/* Whether event `e` (< E) is in the byte mask `bytes`. */
static uint8_t has_event(const uint8_t *bytes, uint8_t e)
{
    return (uint8_t)(((unsigned)bytes[e >> 3] >> (e & 7u)) & 1u);
}
#endif

/* Docs/semantics.md "Selection policies"; `count` >= 1. Returns 0xFF for no event. A policy
 * this build leaves out (SVM_WITH_*) runs as uniform. */
static uint8_t select_event(svm_vm_t *vm, mask_t enabled, uint8_t count)
{
#if SVM_WITH_FIRST || SVM_WITH_WEIGHTED || SVM_WITH_LEARNED
    uint8_t policy = (uint8_t)(VM_OPTIONS(vm) & SVM_POLICY_MASK), e;
#endif
#if SVM_WITH_FIRST || SVM_WITH_LEARNED
    uint8_t bytes[SVM_MASK_BYTES];
    if (policy == SVM_POLICY_LEARNED || policy == SVM_POLICY_FIRST) {
        mask_store(bytes, enabled, SVM_MASK_BYTES);    /* past the image's events: 0 */
    }
#endif
#if SVM_WITH_LEARNED
    if (policy == SVM_POLICY_LEARNED) {
        if (vm->chooser == 0) {
            return 0xFFu;
        }
        e = vm->chooser(vm, bytes, count, vm->chooser_ctx);
        return (e < VM_EVENTS(vm) && has_event(bytes, e)) ? e : 0xFFu;
    }
#endif
#if SVM_WITH_FIRST
    if (policy == SVM_POLICY_FIRST) {
        uint8_t k;
        for (k = 0; k < vm->priority_count; k++) {
            e = vm->priority[k];
            if (e < VM_EVENTS(vm) && has_event(bytes, e)) {
                return e;
            }
        }
        return nth_event(enabled, 0);
    }
#endif
#if SVM_WITH_WEIGHTED
    if (policy == SVM_POLICY_WEIGHTED && count != 1u) {
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
#endif
    /* One call of nth_event for one event and for the uniform draw (no draw for one event): at
     * -O3 on AVR both are inlined, so each further call would be another copy in flash. */
    return nth_event(enabled, count == 1u ? 0u : uniform_index(svm_random(vm), count));
}

/* Docs/semantics.md step 1: the check values of the uncontrollable events, in input order
 * (`first`: the public ones, then `second`: the private ones). The binding table and dispatch
 * are read once per step (callbacks must not rebind during a step). */
static SVM_INLINE mask_t poll(svm_vm_t *vm, mask_t first, mask_t second)
{
#if SVM_WITH_BINDINGS
    const svm_binding_t *bindings = vm->bindings;
    uint8_t cap = bindings != 0 ? vm->bindings_cap : 0u;
#endif
#if FLAT_MASKS
    svm_dispatch_fn dispatch = vm->dispatch;
    mask_t current = 0, todo = SVM_WITH_PUBLIC ? first : second, bit;
    count_t pass, event;
    for (pass = SVM_WITH_PUBLIC ? 0u : 1u; pass < 2u; pass++, todo = second) {
        for (event = 0, bit = 1u; todo != 0u; todo = (mask_t)(todo >> 1), bit = (mask_t)(bit << 1), event++) {
            uint8_t occurs;
#if SVM_WITH_BINDINGS
            svm_check_fn check;
#endif
            if (!(todo & 1u)) {
                continue;
            }
#if SVM_WITH_BINDINGS
            if (event < cap && (check = bindings[event].check) != 0) {     /* read once */
                occurs = check(bindings[event].data) != 0;
            } else
#endif
            {
                occurs = dispatch != 0 && dispatch(vm, event, SVM_OP_CHECK) != 0;
            }
            if (occurs) {
                current = (mask_t)(current | bit);
            }
        }
    }
    return current;
#else
    svm_dispatch_fn dispatch = vm->dispatch;
    uint8_t pass, i, at, current[SVM_MASK_BYTES];
    cursor_t c;
    for (i = 0; i < SVM_MASK_BYTES; i++) {
        current[i] = 0;
    }
    /* Without the public-first pass (SVM_WITH_PUBLIC = 0) `first` is empty: one pass. */
    for (pass = SVM_WITH_PUBLIC ? 0u : 1u, cursor_start(&c, SVM_WITH_PUBLIC ? first : second); pass < 2u;
         pass++, cursor_start(&c, second)) {
        for (at = 0; at < SVM_MASK_BYTES; at++, cursor_skip_byte(&c)) {     /* a zero byte polls none */
            uint8_t todo = cursor_byte(&c), bit = 1, event = c.base, occurred = 0;
            for (; todo != 0u; todo = (uint8_t)(todo >> 1), bit = (uint8_t)(bit << 1), event++) {
                uint8_t occurs;
#if SVM_WITH_BINDINGS
                svm_check_fn check;
#endif
                if (!(todo & 1u)) {
                    continue;
                }
#if SVM_WITH_BINDINGS
                if (event < cap && (check = bindings[event].check) != 0) {     /* read once */
                    occurs = check(bindings[event].data) != 0;
                } else
#endif
                {
                    occurs = dispatch != 0 && dispatch(vm, event, SVM_OP_CHECK) != 0;
                }
                if (occurs) {
                    occurred |= bit;
                }
            }
            current[at] |= occurred;
        }
    }
    return mask_load(current);
#endif
}

/* Docs/semantics.md step 2: the events that occur among those whose check was `current`: all
 * of them with level inputs, with edge inputs those whose check was not true at the previous
 * step; the check values are remembered for the next. `options` are the step's, as it began. */
static SVM_INLINE mask_t occurrence(svm_vm_t *vm, mask_t current, uint8_t options)
{
    mask_t occurring = current;
    if (options & SVM_INPUTS_EDGE) {
        occurring = mask_and_not(current, mask_load(vm->previous));
    }
    mask_store(vm->previous, current, SVM_MASK_BYTES);
    return occurring;
}

/* Docs/semantics.md step 4: whether the step goes on to choose a controllable event (with
 * if-quiet control, not after an input occurred). */
static SVM_INLINE uint8_t control_continues(uint8_t options, mask_t occurring)
{
    return !(mask_any(occurring) && (options & SVM_CONTROL_IF_QUIET));
}

/* The step for masks of `m` bytes. Called with the compile-time SVM_MASK_BYTES when the image's
 * masks have exactly that width (builds with the model's exact limits): the compiler then
 * folds the record sizes and reads each mask in one go. */
static SVM_INLINE uint8_t step_m(svm_vm_t *vm, uint8_t m)
{
    const uint8_t *img = VM_IMAGE(vm);
    uint8_t src = VM_SOURCE(vm), options = VM_OPTIONS(vm);
    count_t fired = 0, pass, count, event;
    mask_t valid = valid_events(vm);
    mask_t controllable = mask_and(mask_read(src, img + CONTROLLABLE_AT, m), valid);
#if SVM_WITH_PUBLIC
    mask_t public_mask = mask_read(src, img + PUBLIC_AT(m), m);
#else
    /* The image has no public uncontrollable event (svm_load_P), the only ones the input order
     * puts first: the order is the one of no public event. */
    const mask_t public_mask = MASK_NONE;
#endif
    mask_t uncontrollable = mask_and_not(valid, controllable);
    /* 1. Poll, in input order: public uncontrollable events, then private ones. 2. Occurrence. */
    mask_t occurring = occurrence(vm, poll(vm, mask_and(uncontrollable, public_mask),
                                           mask_and_not(uncontrollable, public_mask)), options);
#if FLAT_MASKS
    mask_t firing = SVM_WITH_PUBLIC ? mask_and(occurring, public_mask) : occurring;
    /* 3. Apply inputs, public (pass 0) then private (pass 1); then the selected event (pass 2),
     * all from this one loop (below). */
    for (pass = SVM_WITH_PUBLIC ? 0u : 1u;; pass++) {
        mask_t bit = 1u;
        for (event = 0; firing != 0u; firing = (mask_t)(firing >> 1), bit = (mask_t)(bit << 1), event++) {
            if (firing & 1u) {
                fire(vm, event, bit, m);
                fired++;
            }
        }
        if (pass == 0u) {
            firing = mask_and_not(occurring, public_mask);
            continue;
        }
        if (pass == 1u && control_continues(options, occurring)) {
            mask_t enabled = enabled_set(vm, controllable, m);
            /* Only the learned policy's chooser may refuse (0xFF). */
            if ((count = mask_count(enabled)) != 0u &&
                ((event = select_event(vm, enabled, count)) != 0xFFu || !SVM_WITH_LEARNED)) {
                firing = (mask_t)((mask_t)1u << event);
                continue;
            }
        }
        return (uint8_t)fired;
    }
#else
    cursor_t firing;
    /* 3. Apply inputs: the occurring events in input order, public (pass 0) then private
     * (pass 1); then the selected event (pass 2). All fire from this one loop, so that -O3
     * inlines fire once on AVR: a second call for the control phase, a second copy, put the
     * largest model's Kilobot core over its budget (docs/footprint.md, "Cost per step"). */
    for (pass = SVM_WITH_PUBLIC ? 0u : 1u,
         cursor_start(&firing, SVM_WITH_PUBLIC ? mask_and(occurring, public_mask) : occurring);; pass++) {
        for (; cursor_any(&firing); cursor_skip_byte(&firing)) {
            uint8_t todo = cursor_byte(&firing), bit = 1;
            for (event = firing.base; todo != 0u; todo = (uint8_t)(todo >> 1), bit = (uint8_t)(bit << 1), event++) {
                if (todo & 1u) {
                    /* Byte 0 spelled out for 1-byte masks: the compiler then drops fire's
                     * byte arithmetic (docs/footprint.md, "Cost per step"). */
                    fire(vm, event, m == 1u ? 0u : (uint8_t)(firing.base >> 3), bit, m);
                    fired++;
                }
            }
        }
        if (pass == 0u) {
            cursor_start(&firing, mask_and_not(occurring, public_mask));
            continue;
        }
        /* 4. Control phase; 5. enabled set; 6. selection. */
        if (pass == 1u && control_continues(options, occurring)) {
            mask_t enabled = enabled_set(vm, controllable, m);
            if ((count = mask_count(enabled)) != 0u && (event = select_event(vm, enabled, count)) != 0xFFu) {
                cursor_single(&firing, event);
                continue;
            }
        }
        return fired;
    }
#endif
}

uint8_t svm_step(svm_vm_t *vm)
{
    if (vm->image == 0) {
        return 0;
    }
#if !SVM_MASK_EXACT
    if (VM_MASK_BYTES(vm) != SVM_MASK_BYTES) {
        return step_m(vm, MASK_WIDTH(VM_MASK_BYTES(vm)));
    }
#endif
    return step_m(vm, SVM_MASK_BYTES);
}

#if SVM_SCT_EXACT
/* Nadzoru's exact step (swarmvm_sct.c, declared in swarmvm_sct.h) applies events one at a time
 * in its file's order; only that build compiles this second caller of fire. */
void svm_fire_event(svm_vm_t *vm, uint8_t event)
{
    if (vm->image != 0 && event < VM_EVENTS(vm)) {
#if FLAT_MASKS
        fire(vm, event, (mask_t)((mask_t)1u << event), SVM_MASK_BYTES);
#else
        fire(vm, event, (uint8_t)(event >> 3), (uint8_t)(1u << (event & 7u)), VM_MASK_BYTES(vm));
#endif
    }
}
#endif

/* ---- inspection ---------------------------------------------------------------------------- */

uint8_t svm_num_events(const svm_vm_t *vm)
{
    return LOADED_EVENTS(vm);
}

uint8_t svm_num_supervisors(const svm_vm_t *vm)
{
    return LOADED_SUPERVISORS(vm);
}

uint8_t svm_mask_bytes(const svm_vm_t *vm)
{
    return LOADED_MASK_BYTES(vm);
}

SVM_COLD uint16_t svm_first_state(const svm_vm_t *vm, uint8_t supervisor)
{
    if (vm->image == 0 || supervisor >= LOADED_SUPERVISORS(vm)) {
        return 0;
    }
    return RD16(vm, SUP_AT(vm, supervisor) + VM_MASK_BYTES(vm));
}

uint16_t svm_state(const svm_vm_t *vm, uint8_t supervisor)
{
    if (vm->image == 0 || supervisor >= LOADED_SUPERVISORS(vm)) {
        return 0;
    }
    return (uint16_t)(vm->state[supervisor] - svm_first_state(vm, supervisor));
}

uint16_t svm_global_state(const svm_vm_t *vm, uint8_t supervisor)
{
    return (vm->image == 0 || supervisor >= LOADED_SUPERVISORS(vm)) ? 0u : vm->state[supervisor];
}

uint16_t svm_num_states(const svm_vm_t *vm)
{
    return vm->image == 0 ? 0u : RD16(vm, SVM_AT_NUM_STATES);
}

#if SVM_WITH_VIOLATIONS
uint32_t svm_violations(const svm_vm_t *vm)
{
    return vm->violations;
}
#endif

uint8_t svm_is_controllable(const svm_vm_t *vm, uint8_t event)
{
    return (uint8_t)(event < LOADED_EVENTS(vm) && (RD(vm, CONTROLLABLE_AT + (event >> 3)) & (1u << (event & 7u))));
}

uint8_t svm_is_public(const svm_vm_t *vm, uint8_t event)
{
    return (uint8_t)(event < LOADED_EVENTS(vm) &&
                     (RD(vm, PUBLIC_AT(VM_MASK_BYTES(vm)) + (event >> 3)) & (1u << (event & 7u))));
}

#if SVM_WITH_NAMES
SVM_COLD int svm_event_index_n(const svm_vm_t *vm, const char *name, uint8_t length)
{
    uint16_t pos = vm->names_at;
    uint8_t e, i, len;
    if (vm->image == 0 || pos == 0 || name == 0) {
        return -1;
    }
    for (e = 0; e < LOADED_EVENTS(vm); e++, pos = (uint16_t)(pos + 1u + len)) {
        len = RD(vm, pos);
        if (len == length) {
            for (i = 0; i < len && (uint8_t)name[i] == RD(vm, pos + 1u + i); i++) {
            }
            if (i == len) {
                return e;
            }
        }
    }
    return -1;
}

SVM_COLD int svm_event_index(const svm_vm_t *vm, const char *name)
{
    uint16_t n;
    if (name == 0) {
        return -1;
    }
    if (name[0] == 'E' && name[1] == 'V' && name[2] == '_') {
        name += 3;
    }
    /* a name has at most 255 bytes: a longer string names no event */
    for (n = 0; n < 256u && name[n] != '\0'; n++) {
    }
    return n < 256u ? svm_event_index_n(vm, name, (uint8_t)n) : -1;
}

uint8_t svm_has_names(const svm_vm_t *vm)
{
    return (uint8_t)(vm->image != 0 && vm->names_at != 0);
}

SVM_COLD uint8_t svm_event_name(const svm_vm_t *vm, uint8_t event, char *buf, uint8_t cap)
{
    uint16_t pos;
    uint8_t len, i, n;
    if (cap != 0u) {
        buf[0] = '\0';
    }
    if (vm->image == 0 || vm->names_at == 0 || event >= LOADED_EVENTS(vm)) {
        return 0;
    }
    pos = name_at(vm->image, VM_SOURCE(vm), vm->names_at, event);
    len = RD(vm, pos);
    if (cap != 0u) {
        n = len < cap ? len : (uint8_t)(cap - 1u);     /* the name, cut to leave room for '\0' */
        for (i = 0; i < n; i++) {
            buf[i] = (char)RD(vm, pos + 1u + i);
        }
        buf[n] = '\0';
    }
    return len;
}
#endif /* SVM_WITH_NAMES */

uint8_t svm_image_byte(const svm_vm_t *vm, uint16_t at)
{
    return RD(vm, at);
}
