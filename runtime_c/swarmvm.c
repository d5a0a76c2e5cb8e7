/*
 * swarmvm C VM core (see swarmvm.h). The tables are read in place from the image; a
 * transition is found with the state's `defined` mask and a popcount (docs/image-format.md),
 * so a step costs a few mask operations per supervisor whatever the automata's size.
 */
#include "swarmvm.h"

#define HEADER_SIZE 16u
#define FLAG_NAMES 0x01u
#define FLAG_PROBS 0x02u
#define FORMAT_VERSION 1u
#define Q15_ONE 32768u
#define SEED_FOR_ZERO 0x9E3779B9UL

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

#define RD(vm, at) rd_raw((vm)->image, (vm)->in_flash, (uint16_t)(at))
#define RD16(vm, at) rd16_raw((vm)->image, (vm)->in_flash, (uint16_t)(at))

/* The same through a pointer into the image, for the step's loops (no base + offset sums). */
#define PEEK(source, p) READ((p), (source), 0)
static uint16_t peek16(uint8_t source, const uint8_t *p)
{
    return (uint16_t)(PEEK(source, p) | ((uint16_t)PEEK(source, p + 1) << 8));
}

/* Section layout, from the header fields (docs/image-format.md). */
#define CONTROLLABLE_AT HEADER_SIZE
#define PUBLIC_AT(m) (HEADER_SIZE + (uint16_t)(m))
#define SUPS_AT(m) (HEADER_SIZE + 2u * (uint16_t)(m))
#define SUP_SIZE(m) ((uint16_t)(m) + 6u)
#define STATE_SIZE(m) ((uint16_t)(m) + 2u)
#define SUP_AT(vm, s) (SUPS_AT((vm)->mask_bytes) + (uint16_t)(s) * SUP_SIZE((vm)->mask_bytes))
/* vm->state[s] is the supervisor's *global* state number: its record is at
 * states_at + state * STATE_SIZE(m), found without reading the supervisor's first state. */

/* Inlining hint for the step's helpers (C99 `inline` on a static function). */
#define SVM_INLINE inline

/* A loaded image's mask width, clamped to 1..SVM_MASK_BYTES for the compiler's sake (load has
 * checked it already), so that loops over it provably stay inside the VM's mask arrays. */
#define MASK_WIDTH(m) ((uint8_t)((m) - 1u) < SVM_MASK_BYTES ? (uint8_t)(m) : (uint8_t)1u)

static uint8_t popcount8(uint8_t x)
{
    x = (uint8_t)(x - ((x >> 1) & 0x55u));
    x = (uint8_t)((x & 0x33u) + ((x >> 2) & 0x33u));
    return (uint8_t)((x + (x >> 4)) & 0x0Fu);
}

/* Mask of the valid event bits of mask byte `i` (the last byte may be partly padding). */
static uint8_t valid_bits(uint8_t num_events, uint8_t i)
{
    uint8_t left = (uint8_t)(num_events - 8u * i);
    return left >= 8u ? 0xFFu : (uint8_t)(0xFFu >> (8u - left));
}

/* ---- checksum and validation ------------------------------------------------------------- */

static uint16_t crc16(const uint8_t *image, uint8_t source, uint16_t length)
{
    uint16_t crc = 0xFFFFu;
    uint16_t i;
    uint8_t bit;
    for (i = 0; i < length; i++) {
        crc ^= rd_raw(image, source, i);
        for (bit = 0; bit < 8u; bit++) {
            crc = (crc & 1u) ? (uint16_t)((crc >> 1) ^ 0x8408u) : (uint16_t)(crc >> 1);
        }
    }
    return crc;
}

/* What svm_load needs to know once an image has been accepted. */
typedef struct layout {
    uint16_t states_at, targets_at, probs_at, names_at;
} layout_t;

/* Every index the step follows must stay inside the image: check them once here. */
static int check_indices(const uint8_t *image, uint8_t source, const layout_t *lay)
{
    uint8_t m = rd_raw(image, source, 13), width = rd_raw(image, source, 12);
    uint8_t n = rd_raw(image, source, 7);
    uint16_t total_states = rd16_raw(image, source, 8), total_trans = rd16_raw(image, source, 10);
    uint16_t expected_first = 0;
    uint8_t s;
    for (s = 0; s < n; s++) {
        uint16_t at = (uint16_t)(SUPS_AT(m) + (uint16_t)s * (m + 6u) + m);
        uint16_t first = rd16_raw(image, source, at);
        uint16_t count = rd16_raw(image, source, (uint16_t)(at + 2u));
        uint16_t init = rd16_raw(image, source, (uint16_t)(at + 4u));
        uint16_t q;
        if (first != expected_first || count == 0 || init >= count || count > total_states - first) {
            return SVM_ERR_LAYOUT;
        }
        for (q = 0; q < count; q++) {
            uint16_t st = (uint16_t)(lay->states_at + (uint16_t)(first + q) * (m + 2u));
            uint16_t succ = rd16_raw(image, source, (uint16_t)(st + m));
            uint16_t defined = 0, k;
            uint8_t i;
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

static int validate(const uint8_t *image, uint8_t source, uint16_t length, layout_t *lay)
{
    uint8_t flags, e, n, width, m;
    uint16_t states, trans, end, i;
    uint32_t pos;
    if (image == 0 || length < HEADER_SIZE + 2u || rd16_raw(image, source, 14) != length) {
        return SVM_ERR_LENGTH;
    }
    if (rd_raw(image, source, 0) != 'S' || rd_raw(image, source, 1) != 'V' ||
        rd_raw(image, source, 2) != 'M' || rd_raw(image, source, 3) != 'I') {
        return SVM_ERR_MAGIC;
    }
    if (rd_raw(image, source, 4) != FORMAT_VERSION) {
        return SVM_ERR_VERSION;
    }
    end = (uint16_t)(length - 2u);
    if (crc16(image, source, end) != rd16_raw(image, source, end)) {
        return SVM_ERR_CRC;
    }
    flags = rd_raw(image, source, 5);
    e = rd_raw(image, source, 6);
    n = rd_raw(image, source, 7);
    states = rd16_raw(image, source, 8);
    trans = rd16_raw(image, source, 10);
    width = rd_raw(image, source, 12);
    m = rd_raw(image, source, 13);
    if (e == 0 || n == 0 || (width != 1u && width != 2u) || m != (uint8_t)((e + 7u) / 8u)) {
        return SVM_ERR_LAYOUT;
    }
#if SVM_MASK_EXACT
    if (m != SVM_MASK_BYTES) {
        return SVM_ERR_LIMITS;
    }
#endif
    /* Section offsets in 32 bits: a corrupt header must not wrap around. */
    pos = HEADER_SIZE + 2u * (uint32_t)m + (uint32_t)n * (m + 6u);
    lay->states_at = (uint16_t)pos;
    pos += (uint32_t)states * (m + 2u);
    lay->targets_at = (uint16_t)pos;
    pos += (uint32_t)trans * width;
    lay->probs_at = 0;
    if (flags & FLAG_PROBS) {
        lay->probs_at = (uint16_t)pos;
        pos += 2u * (uint32_t)trans;
    }
    lay->names_at = 0;
    if (pos > end) {
        return SVM_ERR_LAYOUT;
    }
    if (flags & FLAG_NAMES) {
        lay->names_at = (uint16_t)pos;
        for (i = 0; i < e; i++) {
            if (pos >= end) {
                return SVM_ERR_LAYOUT;
            }
            pos += 1u + rd_raw(image, source, (uint16_t)pos);
        }
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
    uint16_t old_pos = name_at(vm->image, vm->in_flash, vm->names_at, old_event);
    uint8_t old_len = RD(vm, old_pos);
    uint8_t e, count = rd_raw(image, source, 6), i;
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
    uint8_t map[SVM_MAX_EVENTS];
    uint8_t moved[SVM_MASK_BYTES];
    uint8_t e, cap = vm->bindings_cap;
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
        moved[e >> 3] |= (uint8_t)(1u << (e & 7u));
        to = map[e];
        while (to < limit && map[to] != 0xFFu && !(moved[to >> 3] & (1u << (to & 7u)))) {
            svm_binding_t held = vm->bindings[to];
            vm->bindings[to] = carry;
            moved[to >> 3] |= (uint8_t)(1u << (to & 7u));
            carry = held;
            to = map[to];
        }
        vm->bindings[to] = carry;
    }
    return SVM_OK;
}

static int load(svm_vm_t *vm, const uint8_t *image, uint16_t length, uint8_t source)
{
    layout_t lay;
    int result = validate(image, source, length, &lay);
    if (result != SVM_OK) {
        return result;
    }
    if (vm->image != 0 && vm->bindings != 0 && vm->names_at != 0) {
        result = rebind_by_name(vm, image, source, &lay);
        if (result != SVM_OK) {
            return result;
        }
    }
    vm->image = image;
    vm->in_flash = source;
    vm->states_at = lay.states_at;
    vm->targets_at = lay.targets_at;
    vm->probs_at = lay.probs_at;
    vm->names_at = lay.names_at;
    vm->num_events = RD(vm, 6);
    vm->num_supervisors = RD(vm, 7);
    vm->width = RD(vm, 12);
    vm->mask_bytes = RD(vm, 13);
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
    vm->priority_count = events != 0 ? count : 0u;
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
 * `bit`) from the state whose record is `st`; NO_TRANSITION when it has none (an index is
 * below T <= 65535, so the value is free). */
#define NO_TRANSITION 0xFFFFu
static uint16_t transition(uint8_t src, const uint8_t *st, uint8_t m, uint8_t byte, uint8_t bit)
{
    uint8_t defined = PEEK(src, st + byte);
    uint16_t rank;
    const uint8_t *below;
    if (!(defined & bit)) {
        return NO_TRANSITION;
    }
    rank = popcount8((uint8_t)(defined & (bit - 1u)));
    for (below = st; byte != 0u; below++, byte--) {
        rank = (uint16_t)(rank + popcount8(PEEK(src, below)));
    }
    return (uint16_t)(peek16(src, st + m) + rank);
}

static void violation(svm_vm_t *vm, uint8_t event, uint8_t s)
{
    if (vm->violations != 0xFFFFu) {
        vm->violations++;
    }
    if (vm->on_violation != 0) {
        vm->on_violation(vm, event, s);
    }
}

/* Docs/semantics.md step 3: move every supervisor that has the event, count violations, then
 * run the event's action. Supervisor records are walked in order, without multiplications.
 * `m` is the mask width: see enabled_set for why it is a parameter. */
static SVM_INLINE void apply_m(svm_vm_t *vm, uint8_t event, uint8_t m)
{
    const uint8_t *img = vm->image;
    const uint8_t *states = img + vm->states_at, *targets = img + vm->targets_at;
    const uint8_t *sup = img + SUPS_AT(m);
    svm_state_t *state = vm->state;
    uint8_t src = vm->in_flash, n = vm->num_supervisors, narrow = vm->width == 1u;
    uint8_t byte = (uint8_t)(event >> 3), bit = (uint8_t)(1u << (event & 7u)), s;
    for (s = 0; s < n; s++, sup += SUP_SIZE(m)) {
        uint16_t t, local;
        if (!(PEEK(src, sup + byte) & bit)) {
            continue;
        }
        t = transition(src, states + (uint16_t)state[s] * STATE_SIZE(m), m, byte, bit);
        if (t == NO_TRANSITION) {
            violation(vm, event, s);
            continue;
        }
        local = narrow ? PEEK(src, targets + t) : peek16(src, targets + 2u * t);
        state[s] = (svm_state_t)(peek16(src, sup + m) + local);
    }
    run_action(vm, event);
}

static void apply_exact(svm_vm_t *vm, uint8_t event)
{
    apply_m(vm, event, SVM_MASK_BYTES);
}

#if SVM_MASK_EXACT
#define apply apply_exact
#else
static void apply_any(svm_vm_t *vm, uint8_t event)
{
    apply_m(vm, event, MASK_WIDTH(vm->mask_bytes));
}

static void apply(svm_vm_t *vm, uint8_t event)
{
    if (vm->mask_bytes == SVM_MASK_BYTES) {
        apply_exact(vm, event);
    } else {
        apply_any(vm, event);
    }
}
#endif

/* The enabled set for masks of `m` bytes. Called with the compile-time SVM_MASK_BYTES when the
 * image's masks have exactly that width (builds with the model's exact limits), the compiler
 * then unrolls the byte loops and keeps the mask in registers: about 3x faster on AVR. */
static SVM_INLINE uint8_t enabled_set(const svm_vm_t *vm, uint8_t *enabled, uint8_t m)
{
    const uint8_t *img = vm->image, *sup = img + SUPS_AT(m), *states = img + vm->states_at;
    const svm_state_t *state = vm->state;
    uint8_t src = vm->in_flash, n = vm->num_supervisors, i, s, count = 0;
    uint8_t mask[SVM_MASK_BYTES];   /* local, so that it can live in registers */
    for (i = 0; i < m; i++) {
        mask[i] = PEEK(src, img + CONTROLLABLE_AT + i);
    }
    mask[m - 1u] &= valid_bits(vm->num_events, (uint8_t)(m - 1u));
    for (s = n; s != 0u; s--, sup += SUP_SIZE(m)) {
        const uint8_t *st = states + (uint16_t)*state++ * STATE_SIZE(m);
        for (i = 0; i < m; i++) {
            mask[i] &= (uint8_t)(PEEK(src, st + i) | (uint8_t)~PEEK(src, sup + i));
        }
    }
    for (i = 0; i < m; i++) {
        enabled[i] = mask[i];
        count = (uint8_t)(count + popcount8(mask[i]));
    }
    return count;
}

uint8_t svm_enabled(const svm_vm_t *vm, uint8_t *enabled)
{
    if (vm->image == 0) {
        return 0;
    }
#if !SVM_MASK_EXACT
    if (vm->mask_bytes != SVM_MASK_BYTES) {
        return enabled_set(vm, enabled, MASK_WIDTH(vm->mask_bytes));
    }
#endif
    return enabled_set(vm, enabled, SVM_MASK_BYTES);
}

uint32_t svm_weight(const svm_vm_t *vm, uint8_t event)
{
    const uint8_t *img = vm->image, *sup, *states, *probs;
    uint32_t weight = Q15_ONE;
    uint8_t src = vm->in_flash, m = vm->mask_bytes, byte = (uint8_t)(event >> 3), bit = (uint8_t)(1u << (event & 7u)), s;
    if (vm->probs_at == 0) {
        return weight;
    }
    sup = img + SUPS_AT(m);
    states = img + vm->states_at;
    probs = img + vm->probs_at;
    for (s = 0; s < vm->num_supervisors; s++, sup += SUP_SIZE(m)) {
        uint16_t t;
        if (!(PEEK(src, sup + byte) & bit)) {
            continue;
        }
        t = transition(src, states + (uint16_t)vm->state[s] * STATE_SIZE(m), m, byte, bit);
        if (t != NO_TRANSITION) {
            weight = (weight * peek16(src, probs + 2u * t)) >> 15;
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

/* Docs/semantics.md "Selection policies"; `count` >= 1. Returns 0xFF for no event. */
static uint8_t select_event(svm_vm_t *vm, const uint8_t *enabled, uint8_t count)
{
    uint8_t m = vm->mask_bytes, policy = (uint8_t)(vm->options & SVM_POLICY_MASK);
    if (policy == SVM_POLICY_LEARNED) {
        uint8_t e;
        if (vm->chooser == 0) {
            return 0xFFu;
        }
        e = vm->chooser(vm, enabled, count, vm->chooser_ctx);
        return (e < vm->num_events && (enabled[e >> 3] & (1u << (e & 7u)))) ? e : 0xFFu;
    }
    if (policy == SVM_POLICY_FIRST) {
        uint8_t k;
        for (k = 0; k < vm->priority_count; k++) {
            uint8_t e = vm->priority[k];
            if (e < vm->num_events && (enabled[e >> 3] & (1u << (e & 7u)))) {
                return e;
            }
        }
        return svm_mask_nth(enabled, m, 0);
    }
    if (count == 1u) {
        return svm_mask_nth(enabled, m, 0);
    }
    if (policy == SVM_POLICY_WEIGHTED) {
        uint32_t total = 0, pick;
        uint8_t k, e;
        for (k = 0; k < count; k++) {
            total += svm_weight(vm, svm_mask_nth(enabled, m, k));
        }
        if (total != 0) {
            pick = svm_random(vm) % total;
            for (k = 0; k < count; k++) {
                uint32_t w;
                e = svm_mask_nth(enabled, m, k);
                w = svm_weight(vm, e);
                if (pick < w) {
                    return e;
                }
                pick -= w;
            }
        }
    }
    return svm_mask_nth(enabled, m, (uint8_t)((((svm_random(vm) >> 16) & 0xFFFFu) * count) >> 16));
}

/* Docs/semantics.md step 1: the check values of the uncontrollable events, in input order
 * (public ones first). `m` as in enabled_set. The binding table and dispatch are read once per
 * step (callbacks must not rebind during a step). */
static SVM_INLINE void poll_m(svm_vm_t *vm, uint8_t *current, uint8_t m)
{
    const uint8_t *img = vm->image;
    const svm_binding_t *bindings = vm->bindings;
    svm_dispatch_fn dispatch = vm->dispatch;
    uint8_t src = vm->in_flash, cap = bindings != 0 ? vm->bindings_cap : 0u, pass, i, bit;
    for (i = 0; i < m; i++) {
        current[i] = 0;
    }
    for (pass = 0; pass < 2u; pass++) {
        for (i = 0; i < m; i++) {
            uint8_t pub = PEEK(src, img + PUBLIC_AT(m) + i), event = (uint8_t)(8u * i);
            uint8_t polled = (uint8_t)(~PEEK(src, img + CONTROLLABLE_AT + i) & (pass == 0u ? pub : (uint8_t)~pub));
            if (i == m - 1u) {
                polled &= valid_bits(vm->num_events, i);
            }
            for (bit = 1; polled != 0u; bit = (uint8_t)(bit << 1), event++) {
                uint8_t occurs;
                if ((polled & bit) == 0u) {
                    continue;
                }
                polled &= (uint8_t)~bit;
                if (event < cap && bindings[event].check != 0) {
                    occurs = bindings[event].check(bindings[event].data) != 0;
                } else {
                    occurs = dispatch != 0 && dispatch(vm, event, SVM_OP_CHECK) != 0;
                }
                if (occurs) {
                    current[i] |= bit;
                }
            }
        }
    }
}

/* Removes and returns the lowest event of `mask` (m bytes), 0xFF when it is empty. */
static uint8_t take_lowest(uint8_t *mask, uint8_t m)
{
    uint8_t i, bit, event;
    for (i = 0; i < m; i++) {
        if (mask[i] != 0u) {
            for (bit = 1, event = (uint8_t)(8u * i); (mask[i] & bit) == 0u; bit = (uint8_t)(bit << 1)) {
                event++;
            }
            mask[i] &= (uint8_t)~bit;
            return event;
        }
    }
    return 0xFFu;
}

uint8_t svm_step(svm_vm_t *vm)
{
    /* Occurring public and private inputs still to apply, then the control phase: one loop with
     * a single apply site, which the compiler inlines. */
    uint8_t public_in[SVM_MASK_BYTES], private_in[SVM_MASK_BYTES], enabled[SVM_MASK_BYTES];
    uint8_t m = MASK_WIDTH(vm->mask_bytes), fired = 0, any = 0, controlled = 0, i;
    if (vm->image == 0) {
        return 0;
    }
    /* 1. Poll, in input order: public uncontrollable events, then private ones. 2. Occurrence. */
#if SVM_MASK_EXACT
    poll_m(vm, public_in, SVM_MASK_BYTES);
#else
    if (m == SVM_MASK_BYTES) {
        poll_m(vm, public_in, SVM_MASK_BYTES);
    } else {
        poll_m(vm, public_in, MASK_WIDTH(m));
    }
#endif
    for (i = 0; i < m; i++) {
        uint8_t now = public_in[i], pub = RD(vm, PUBLIC_AT(m) + i);
        if (vm->options & SVM_INPUTS_EDGE) {
            public_in[i] &= (uint8_t)~vm->previous[i];
        }
        vm->previous[i] = now;
        any |= public_in[i];
        private_in[i] = (uint8_t)(public_in[i] & (uint8_t)~pub);
        public_in[i] &= pub;
    }
    /* 4. Control phase: with if-quiet, none after an input. */
    if (any && (vm->options & SVM_CONTROL_IF_QUIET)) {
        controlled = 1;
    }
    for (;;) {
        /* 3. The occurring events in input order; then 5-6: enabled set, selection. */
        uint8_t event = take_lowest(public_in, m);
        if (event == 0xFFu) {
            event = take_lowest(private_in, m);
        }
        if (event == 0xFFu) {
            uint8_t count;
            if (controlled) {
                break;
            }
            controlled = 1;
            count = svm_enabled(vm, enabled);
            if (count == 0u || (event = select_event(vm, enabled, count)) == 0xFFu) {
                break;
            }
        }
        apply(vm, event);
        fired++;
    }
    return fired;
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

uint16_t svm_state(const svm_vm_t *vm, uint8_t supervisor)
{
    if (vm->image == 0 || supervisor >= vm->num_supervisors) {
        return 0;
    }
    return (uint16_t)(vm->state[supervisor] - RD16(vm, SUP_AT(vm, supervisor) + vm->mask_bytes));
}

uint16_t svm_violations(const svm_vm_t *vm)
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
    pos = name_at(vm->image, vm->in_flash, vm->names_at, event);
    len = RD(vm, pos);
    for (i = 0; i < len && (uint16_t)i + 1u < cap; i++) {
        buf[i] = (char)RD(vm, pos + 1u + i);
    }
    if (cap != 0u) {
        buf[i] = '\0';
    }
    return len;
}
