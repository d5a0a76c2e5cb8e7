/*
 * swarmvm C VM core: runs compiled supervisors by interpreting the portable table image
 * (docs/image-format.md) with the execution semantics of docs/semantics.md.
 *
 * C99, no heap, no stdio, no floating point. The image is never copied: the VM keeps a
 * pointer to it and a few section offsets, so its RAM is the current states, the previous
 * check values (edge mode), the generator state, those offsets and the hooks (runtime_c/README.md,
 * "Figures"). The image may sit in flash: on AVR, svm_load_P() takes
 * a PROGMEM image and table reads go through pgm_read_byte/word/dword; svm_load() takes an image
 * in RAM, svm_load_E() one in EEPROM (loaded at run time). Elsewhere all are plain reads.
 *
 * Compile-time limits (set by the build, e.g. -DSVM_MAX_EVENTS=10):
 *   SVM_MAX_EVENTS        largest E an image may have            (default 64)
 *   SVM_MAX_SUPERVISORS   largest N an image may have            (default 16)
 *   SVM_MAX_STATES        most states of all supervisors; 256 or
 *                         less stores a state in one byte        (default 65535)
 *   SVM_MASK_EXACT        1: accept only images whose masks are exactly SVM_MASK_BYTES wide
 *                         (E in the same block of 8 as SVM_MAX_EVENTS); the step then has
 *                         one, unrolled code path: smaller and faster (default 0)
 *   SVM_IMAGE_SOURCES     AVR only: where images may live: SVM_FLASH_OR_RAM (default),
 *                         SVM_FLASH_ONLY (svm_load_P only; faster, smaller), SVM_RAM_ONLY,
 *                         or SVM_ANY_SOURCE (also EEPROM, svm_load_E)
 *   SVM_POPCOUNT_TABLE    1: count the bits of a mask byte with a 256-byte table in flash
 *                         (default on AVR, where it shortens a step (docs/footprint.md), but at -Os,
 *                         which asks for flash first, and on hosts; not on bare-metal ARM),
 *                         0: arithmetic
 *   SVM_CRC_TABLE         1: the image checksum (CRC-16/MCRF4XX, swarmvm.c) looks up four
 *                         512-byte tables, four image bytes a step (default on hosts),
 *                         0: computes each byte with shifts (default on AVR, by avr-libc's
 *                         _crc_ccitt_update, and on bare-metal ARM). Hosts only: 1 on AVR
 *                         is an #error (the tables would be copied into RAM)
 *
 * Features (each 1 by default; a build that does not use one sets it to 0 and its code is not
 * compiled: the generated Kilobot Makefile keeps only what its program calls):
 *   SVM_WITH_BINDINGS     the runtime binding table (svm_set_bindings, svm_bind) and its
 *                         rebinding by name on a swap; without it callbacks are the dispatch's
 *   SVM_WITH_NAMES        reading event names (svm_event_index, svm_event_name, svm_has_names)
 *                         and rebinding by name on a swap (bindings, svm_bind_priority); without
 *                         it a swap keeps bindings by index, as for images without names
 *   SVM_WITH_FIRST        policy `first` (svm_set_priority, svm_bind_priority)
 *   SVM_WITH_WEIGHTED     policy `weighted` (and svm_weight)
 *   SVM_WITH_LEARNED      policy `learned` (svm_set_chooser)
 * A policy left out runs as `uniform` when the options ask for it. Loading checks every image
 * the same way whatever the features (same checks, same result codes).
 *
 * Minimal profile (runtime_c/README.md, "The minimal profile"): the image is the generator's own
 * constant, compiled into flash, and is not checked again at run time:
 *   SVM_TRUSTED_IMAGE     the name of that image's symbol (e.g.
 *                         -DSVM_TRUSTED_IMAGE=energy_worker_image, as the generated tables
 *                         define it). svm_load_P then runs that one image without validating
 *                         it (the compiler made every check when it wrote it) and refuses any
 *                         other pointer with SVM_ERR_SOURCE; svm_load, svm_load_E and
 *                         svm_validate do not exist, so no bytes from elsewhere (a stream, EEPROM,
 *                         RAM) can reach the VM unchecked. Implies SVM_IMAGE_SOURCES =
 *                         SVM_FLASH_ONLY and SVM_MASK_EXACT = 1. The limits must be the
 *                         image's exact counts (the generated Makefile's): the step uses them
 *                         as constants, and the load refuses an image of other counts.
 *   SVM_TRUSTED_OPTIONS   the options (SVM_INPUTS_* | SVM_CONTROL_* | SVM_POLICY_*) fixed at
 *                         build, e.g. -DSVM_TRUSTED_OPTIONS=0x01u for edge inputs,
 *                         after-inputs, uniform: the step has that one path. svm_set_options
 *                         still sets the seed; its `options` are stored but not used.
 *                         (Any build may set it; the profile is where it pays.)
 *   SVM_WITH_PUBLIC       0: the model has no public uncontrollable event (the only events the
 *                         input order puts first), so the step has no public-first pass;
 *                         svm_load_P refuses an image with one (SVM_ERR_LIMITS). Only with
 *                         SVM_TRUSTED_IMAGE (an #error otherwise).
 * And for any build:
 *   SVM_WITH_VIOLATIONS   0: no violation counter and no hook (svm_violations,
 *                         svm_set_on_violation not declared; svm_vm_t 6 bytes smaller on AVR).
 *                         A violation still leaves the supervisor where it is, as always: only
 *                         its count and report are gone. Default 1.
 * With the features above set to 0 and -ffunction-sections -Wl,--gc-sections this is the
 * smallest VM (benchmarks/flash_vs_published.py).
 */
#ifndef SWARMVM_H
#define SWARMVM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef SVM_MAX_EVENTS
#define SVM_MAX_EVENTS 64
#endif
#ifndef SVM_MAX_SUPERVISORS
#define SVM_MAX_SUPERVISORS 16
#endif
#ifndef SVM_MAX_STATES
#define SVM_MAX_STATES 65535
#endif
#define SVM_FLASH_OR_RAM 0
#define SVM_FLASH_ONLY 1
#define SVM_RAM_ONLY 2
#define SVM_ANY_SOURCE 3
#ifdef SVM_TRUSTED_IMAGE
/* The trusted image is a constant in flash, read with the model's exact mask width: any other
 * setting would read it as something it is not. */
#ifndef SVM_MASK_EXACT
#define SVM_MASK_EXACT 1
#endif
#ifndef SVM_IMAGE_SOURCES
#define SVM_IMAGE_SOURCES SVM_FLASH_ONLY
#endif
#if !SVM_MASK_EXACT || SVM_IMAGE_SOURCES != SVM_FLASH_ONLY
#error "SVM_TRUSTED_IMAGE runs the generator's image from flash: SVM_MASK_EXACT=1, SVM_IMAGE_SOURCES=SVM_FLASH_ONLY"
#endif
#endif
#ifndef SVM_MASK_EXACT
#define SVM_MASK_EXACT 0
#endif
#ifndef SVM_IMAGE_SOURCES
#define SVM_IMAGE_SOURCES SVM_FLASH_OR_RAM
#endif
#ifndef SVM_POPCOUNT_TABLE
#if defined(__AVR__) ? !defined(__OPTIMIZE_SIZE__) : !(defined(__arm__) && !defined(__linux__))
#define SVM_POPCOUNT_TABLE 1
#else
#define SVM_POPCOUNT_TABLE 0
#endif
#endif

#ifndef SVM_WITH_BINDINGS
#define SVM_WITH_BINDINGS 1
#endif
#ifndef SVM_WITH_NAMES
#define SVM_WITH_NAMES 1
#endif
#ifndef SVM_WITH_FIRST
#define SVM_WITH_FIRST 1
#endif
#ifndef SVM_WITH_WEIGHTED
#define SVM_WITH_WEIGHTED 1
#endif
#ifndef SVM_WITH_LEARNED
#define SVM_WITH_LEARNED 1
#endif
#ifndef SVM_WITH_VIOLATIONS
#define SVM_WITH_VIOLATIONS 1
#endif
#ifndef SVM_WITH_PUBLIC
#define SVM_WITH_PUBLIC 1
#endif
#if !SVM_WITH_PUBLIC && !defined(SVM_TRUSTED_IMAGE)
#error "SVM_WITH_PUBLIC=0 is for the minimal profile (SVM_TRUSTED_IMAGE), whose image has no public event"
#endif

/* The image format's numbers (its limits SVM_FORMAT_MAX_*, which a build's SVM_MAX_* stay
 * within, header offsets, flags, the Q15 one, the result codes), generated from
 * runtime_py/swarmvm_format.py. */
#include "swarmvm_format.h"

#if SVM_MAX_EVENTS < 1 || SVM_MAX_EVENTS > SVM_FORMAT_MAX_EVENTS
#error "SVM_MAX_EVENTS must be 1..255 (the image format's limit)"
#endif
#if SVM_MAX_SUPERVISORS < 1 || SVM_MAX_SUPERVISORS > SVM_FORMAT_MAX_SUPERVISORS
#error "SVM_MAX_SUPERVISORS must be 1..255 (the image format's limit)"
#endif

/* Bytes of an event mask able to hold SVM_MAX_EVENTS events. */
#define SVM_MASK_BYTES ((SVM_MAX_EVENTS + 7) / 8)

/* The violation counter stops here on every runtime (docs/semantics.md). */
#define SVM_MAX_VIOLATIONS 0xFFFFFFFFUL

/* A supervisor's current state, as a global state number (index of its record). */
#if SVM_MAX_STATES < 1 || SVM_MAX_STATES > SVM_FORMAT_MAX_STATES
#error "SVM_MAX_STATES must be 1..65535 (the image format's limit)"
#endif
#if SVM_MAX_STATES <= 256
typedef uint8_t svm_state_t;
#else
typedef uint16_t svm_state_t;
#endif

/* Where constant tables live, and how to read one byte of them. */
#if defined(__AVR__)
#include <avr/pgmspace.h>
#define SVM_PROGMEM PROGMEM
#define SVM_FLASH_BYTE(p) pgm_read_byte(p)
#else
#define SVM_PROGMEM
#define SVM_FLASH_BYTE(p) (*(const uint8_t *)(p))
#endif

/* The table image format (docs/image-format.md): swarmvm_format.h, included above, holds its
 * numbers and the result codes of svm_load and friends (enum svm_result: SVM_OK, SVM_ERR_*).
 * Generated tables refuse to compile against a runtime of another version. */

/* Where an image lives (svm_validate's `source`). */
#define SVM_SOURCE_RAM 0u
#define SVM_SOURCE_FLASH 1u
#define SVM_SOURCE_EEPROM 2u

/* ---- options: one byte of run-time flags, so one binary runs every combination ---------- */
#define SVM_INPUTS_LEVEL 0x00u      /* an event occurs while its check is true (default) */
#define SVM_INPUTS_EDGE 0x01u       /* ... only when its check turned true */
#define SVM_CONTROL_AFTER_INPUTS 0x00u  /* choose a controllable event every step (default) */
#define SVM_CONTROL_IF_QUIET 0x02u  /* ... only when no uncontrollable event occurred */
#define SVM_POLICY_UNIFORM 0x00u    /* xorshift32 pick among the enabled events (default) */
#define SVM_POLICY_FIRST 0x04u      /* the enabled event of lowest rank (svm_set_priority) */
#define SVM_POLICY_WEIGHTED 0x08u   /* Q15 product of transition probabilities */
#define SVM_POLICY_LEARNED 0x0Cu    /* the chooser callback decides (svm_set_chooser) */
#define SVM_POLICY_MASK 0x0Cu

#define SVM_DEFAULT_SEED 1u
#define SVM_ZERO_SEED 0x9E3779B9UL  /* what seed 0, a fixed point of xorshift32, is replaced by */

struct svm_vm;

/* Nadzoru-compatible callback shapes: an action, and a check returning nonzero when the
 * uncontrollable event occurs. `data` is the pointer given at binding. */
typedef void (*svm_action_fn)(void *data);
typedef unsigned char (*svm_check_fn)(void *data);

/* One runtime binding; an array of these (one per event) is supplied by the application. */
typedef struct svm_binding {
    svm_action_fn action;
    svm_check_fn check;
    void *data;
} svm_binding_t;

/* Compile-time dispatch: generated code supplies one function that calls the application's
 * check (op SVM_OP_CHECK, returns nonzero when the event occurs) or action (SVM_OP_ACTION)
 * of `event`, through a switch, so callbacks cost no RAM. */
#define SVM_OP_CHECK 0u
#define SVM_OP_ACTION 1u
typedef uint8_t (*svm_dispatch_fn)(struct svm_vm *vm, uint8_t event, uint8_t op);

/* Learned policy hook (SVM_POLICY_LEARNED): given the mask of enabled controllable events
 * (svm_mask_bytes(vm) bytes, bit e%8 of byte e/8 for event e) and their count (>= 1),
 * return the event to fire. A return value that is not enabled fires nothing this step. */
typedef uint8_t (*svm_chooser_fn)(struct svm_vm *vm, const uint8_t *enabled, uint8_t count,
                                  void *ctx);

/* Called for each supervisor that cannot follow an occurring uncontrollable event. */
typedef void (*svm_violation_fn)(struct svm_vm *vm, uint8_t event, uint8_t supervisor);

/* The VM. Treat the fields as private; use the functions below. */
typedef struct svm_vm {
    const uint8_t *image;       /* the table image (flash or RAM), NULL before a load */
#ifndef SVM_TRUSTED_IMAGE
    uint16_t states_at;         /* offsets of the image's sections (the profile's are constants) */
    uint16_t targets_at;
#endif
#if SVM_WITH_WEIGHTED || SVM_WITH_LEARNED
    uint16_t probs_at;          /* 0 when the image has no probabilities */
#endif
#if SVM_WITH_NAMES
    uint16_t names_at;          /* 0 when the image has no names */
#endif
#ifndef SVM_TRUSTED_IMAGE
    uint8_t num_events;         /* the image's counts (the profile's are the build's limits) */
    uint8_t num_supervisors;
    uint8_t mask_bytes;
#endif
    uint8_t width;              /* bytes of a target state number: 1 or 2 */
#ifndef SVM_TRUSTED_IMAGE
    uint8_t source;             /* where the image lives: SVM_SOURCE_RAM (0), SVM_SOURCE_FLASH
                                   (1) or SVM_SOURCE_EEPROM (2); read it with svm_image_byte
                                   (the profile's is a constant: program memory on AVR) */
#endif
    uint8_t options;            /* SVM_INPUTS_* | SVM_CONTROL_* | SVM_POLICY_* */
#if SVM_WITH_VIOLATIONS
    uint32_t violations;        /* saturates at SVM_MAX_VIOLATIONS */
#endif
    svm_state_t state[SVM_MAX_SUPERVISORS];   /* global state numbers */
    uint8_t previous[SVM_MASK_BYTES];   /* check values of the previous step (edge mode) */
    uint32_t rng;
    uint32_t seed;
#if SVM_WITH_BINDINGS
    svm_binding_t *bindings;    /* optional runtime binding table, `bindings_cap` entries */
    uint8_t bindings_cap;
#endif
    svm_dispatch_fn dispatch;   /* optional compile-time dispatch */
#if SVM_WITH_LEARNED
    svm_chooser_fn chooser;
    void *chooser_ctx;
#endif
#if SVM_WITH_VIOLATIONS
    svm_violation_fn on_violation;
#endif
#if SVM_WITH_FIRST
    const uint8_t *priority;    /* policy `first`: events to rank first, highest first */
    uint8_t *priority_by_name;  /* the same list when a swap rebinds it (svm_bind_priority) */
    uint8_t priority_count;
#endif
} svm_vm_t;

/* ---- life cycle ------------------------------------------------------------------------- */

/* Empty VM: no image, default options (level, after-inputs, uniform), seed 1, no callbacks. */
void svm_init(svm_vm_t *vm);

#ifndef SVM_TRUSTED_IMAGE
/* Validate `image` (`length` bytes, in RAM) and run it from its initial states. On a running
 * VM this is the swap: it happens between two steps, implies a reset, and rebinds runtime
 * bindings by event name when both images carry names. On error nothing changes. Never from a
 * callback while svm_step runs (the step keeps the old image's layout): record the request and
 * load after svm_step returns (docs/semantics.md, "Reset and swap"). */
int svm_load(svm_vm_t *vm, const uint8_t *image, uint16_t length);

/* The same for an image in program memory (PROGMEM on AVR; identical to svm_load elsewhere). */
int svm_load_P(svm_vm_t *vm, const uint8_t *image, uint16_t length);

/* The same for an image in EEPROM (AVR built with SVM_IMAGE_SOURCES = SVM_ANY_SOURCE;
 * SVM_ERR_SOURCE otherwise). `image` is its EEPROM address, not 0 (a null pointer). */
int svm_load_E(svm_vm_t *vm, const uint8_t *image, uint16_t length);

/* Check an image without loading it (same checks and result codes as svm_load); `source` is
 * SVM_SOURCE_RAM, _FLASH or _EEPROM. */
int svm_validate(const uint8_t *image, uint16_t length, uint8_t source);
#else
/* The generator's image, defined by the generated tables (SVM_PROGMEM). */
extern const uint8_t SVM_TRUSTED_IMAGE[];

/* Minimal profile: run the image SVM_TRUSTED_IMAGE names, unchecked, from its initial states (on
 * a running VM: the swap, as svm_load). Any other `image` is refused with SVM_ERR_SOURCE, an
 * image whose counts are not exactly the build's limits with SVM_ERR_LIMITS; `length` is not
 * read (the image says it). */
int svm_load_P(svm_vm_t *vm, const uint8_t *image, uint16_t length);
#endif

/* The image's checksum, CRC-16/MCRF4XX, one byte at a time: start from SVM_CRC16_INIT
 * (swarmvm_format.h). Also the checksum of the learned-parameter store (swarmvm_store.h). */
uint16_t svm_crc16_update(uint16_t crc, uint8_t byte);

/* Initial states, cleared check memory and violation counter, generator re-seeded. */
void svm_reset(svm_vm_t *vm);

/* Options take effect at the next step; the seed at the next reset. A build with
 * SVM_TRUSTED_OPTIONS steps with the build's options whatever `options` says. */
void svm_set_options(svm_vm_t *vm, uint8_t options, uint32_t seed);

/* ---- callbacks -------------------------------------------------------------------------- */

/* Use `table` (capacity `cap` events, cleared here) for svm_bind. */
void svm_set_bindings(svm_vm_t *vm, svm_binding_t *table, uint8_t cap);

/* Bind an action and/or a check (NULL leaves none) to an event index. */
int svm_bind(svm_vm_t *vm, uint8_t event, svm_action_fn action, svm_check_fn check, void *data);

/* Compile-time dispatch, used for every event without a runtime binding. */
void svm_set_dispatch(svm_vm_t *vm, svm_dispatch_fn dispatch);

void svm_set_chooser(svm_vm_t *vm, svm_chooser_fn chooser, void *ctx);

/* Policy `first`: the `count` event indices of `events` (RAM, kept by the caller) rank first,
 * in that order; the others follow by index. NULL / 0 restores plain index order. Indices
 * refer to the loaded image: set the list again after a swap (svm_event_index helps), or
 * use svm_bind_priority. */
void svm_set_priority(svm_vm_t *vm, const uint8_t *events, uint8_t count);

/* The same, with a list the VM may rewrite: a swap then rebinds it by event name, as it does
 * runtime bindings (each index becomes that of the new image's event of the same name; an
 * image lacking one of the names is refused with SVM_ERR_NAMES; an entry that names no event
 * becomes 0xFF, never enabled). */
void svm_bind_priority(svm_vm_t *vm, uint8_t *events, uint8_t count);
#if SVM_WITH_VIOLATIONS
void svm_set_on_violation(svm_vm_t *vm, svm_violation_fn hook);
#endif

/* ---- running ---------------------------------------------------------------------------- */

/* One step. Returns the number of events fired; their actions ran in firing order. */
uint8_t svm_step(svm_vm_t *vm);

/* Fill `enabled` (svm_mask_bytes(vm) bytes) with the enabled controllable events; returns
 * their count. */
uint8_t svm_enabled(const svm_vm_t *vm, uint8_t *enabled);

/* Q15 weight of a controllable event in the current states (policy `weighted`). */
uint32_t svm_weight(const svm_vm_t *vm, uint8_t event);

/* The generator (xorshift32, docs/semantics.md); learners may draw from it. */
uint32_t svm_random(svm_vm_t *vm);

/* ---- inspection ------------------------------------------------------------------------- */

uint8_t svm_num_events(const svm_vm_t *vm);
uint8_t svm_num_supervisors(const svm_vm_t *vm);
uint8_t svm_mask_bytes(const svm_vm_t *vm);
uint16_t svm_state(const svm_vm_t *vm, uint8_t supervisor);

/* States of all supervisors are also numbered together (docs/image-format.md, the states
 * section): the supervisor's current state and its first state in that numbering
 * (svm_global_state = svm_first_state + svm_state), and the number of all states. 0 without an
 * image or for a supervisor out of range. For code that keeps a table row per state, e.g. a
 * learner; they read the image wherever it lives (RAM, flash, EEPROM). */
uint16_t svm_global_state(const svm_vm_t *vm, uint8_t supervisor);
uint16_t svm_first_state(const svm_vm_t *vm, uint8_t supervisor);
uint16_t svm_num_states(const svm_vm_t *vm);
#if SVM_WITH_VIOLATIONS
uint32_t svm_violations(const svm_vm_t *vm);
#endif
uint8_t svm_is_controllable(const svm_vm_t *vm, uint8_t event);
uint8_t svm_is_public(const svm_vm_t *vm, uint8_t event);

/* Index of the event named `name` ("x" or "EV_x"), or -1 (unknown, or image without names). */
int svm_event_index(const svm_vm_t *vm, const char *name);
/* Index of the event whose name is exactly the `length` characters at `name` ("x", no "EV_"
 * taken off; no NUL needed), or -1: e.g. a name svm_event_name copied, with its length. */
int svm_event_index_n(const svm_vm_t *vm, const char *name, uint8_t length);

/* Byte `at` of the loaded image, wherever it lives (flash, RAM, EEPROM): for code that reads
 * the image format itself (docs/image-format.md), e.g. a learner. */
uint8_t svm_image_byte(const svm_vm_t *vm, uint16_t at);

/* Whether the image carries event names (a name may be empty: Nadzoru's event "EV_"). */
uint8_t svm_has_names(const svm_vm_t *vm);

/* Copy the event's name without "EV_" into `buf` (NUL-terminated, cut to cap-1 chars);
 * returns its full length (0 also when the image has no names). */
uint8_t svm_event_name(const svm_vm_t *vm, uint8_t event, char *buf, uint8_t cap);

/* Index of the `n`-th set bit (n from 0) of an event mask of `bytes` bytes; 255 if none. */
uint8_t svm_mask_nth(const uint8_t *mask, uint8_t bytes, uint8_t n);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_H */
