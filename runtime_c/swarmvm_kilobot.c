/*
 * swarmvm on the Kilobot (kilolib, ATmega328P): the runtime the program calls (swarmvm_kilobot.h
 * says what it does: the calls, step rate, messages, seeds, interrupts, streaming).
 */
#include "swarmvm_kilobot.h"

#include <string.h>

#ifdef __AVR__
#include <avr/pgmspace.h>
#include <util/atomic.h>
#define flash_compare memcmp_P
#define flash_copy memcpy_P
#else
#define flash_compare memcmp
#define flash_copy memcpy
/* Other compilers (host builds of the glue, static analysis): no interrupt exists, the block
 * simply runs. */
#define ATOMIC_BLOCK(type) for (uint8_t svm_atomic_once = 1u; svm_atomic_once != 0u; svm_atomic_once = 0u)
#define ATOMIC_RESTORESTATE 0
#endif

#if SVM_STREAM && SVM_IMAGE_SOURCES == SVM_FLASH_ONLY
#error "SVM_STREAM runs an image from RAM: build without SVM_IMAGE_SOURCES=SVM_FLASH_ONLY"
#endif

#define MASK_BYTES ((SVM_MAX_EVENTS + 7u) / 8u)

#if SVM_LEARNED
#if SVM_KILOBOT_EEPROM_FREE + 2UL * SVM_KILOBOT_SLOT_BYTES > 1024UL
#error "SVM_LEARNED: the learned parameters' two slots do not fit the EEPROM above kilolib's area"
#endif
static svl_policy_t policy;
static int32_t theta[SVM_KILOBOT_THETA];
static uint32_t words[SVL_KEEPER_WORDS(SVM_KILOBOT_THETA)];     /* save/load buffer */
static svm_store_t store;
static svl_keeper_t keeper;
#endif

static svm_vm_t vm;
static uint32_t last_step;
/* Set by the program (svm_kilobot_hold), maybe from an interrupt; one byte, so read whole. */
static volatile uint8_t held;

/* Shared with the IR receive interrupt (set there, taken here) and with the Timer0 transmit
 * interrupt (set here, cleared there once sent). */
static volatile uint8_t received[MASK_BYTES];
static volatile uint8_t pending[MASK_BYTES];

/* Owned by the transmit interrupt: the message kilolib is offered and the event it carries. */
static message_t outgoing;
static uint8_t outgoing_event = SVM_KILOBOT_END;

#if SVM_STREAM
/* Chunks queued by the receive interrupt: it fills slot chunk_head and advances chunk_head;
 * loop() copies slot chunk_tail and advances chunk_tail (both inside ATOMIC_BLOCK). */
static volatile uint8_t chunk_slot[SVM_KILOBOT_CHUNK_SLOTS][SVM_CHUNK_BYTES];
static volatile uint8_t chunk_head, chunk_tail;
static volatile uint8_t from_stream;    /* the VM runs the streamed image: chunks are ignored */
static uint8_t stream_buffer[SVM_STREAM_BYTES];
static svm_stream_t stream;
static uint8_t stream_reported;         /* last status given to the controller */
/* Running the streamed image, the VM's event e is this program's event own_event[e] (same
 * name), so the dispatch calls the controller's code for the right event. */
static uint8_t own_event[SVM_MAX_EVENTS];
#endif

static uint8_t wire_event(const svm_kilobot_wire_t *wire)
{
    return SVM_FLASH_BYTE(&wire->event);
}

static uint8_t bit_of(uint8_t event)
{
    return (uint8_t)(1u << (event & 7u));
}

svm_vm_t *svm_kilobot_vm(void)
{
    return &vm;
}

void svm_kilobot_send(uint8_t event)
{
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        pending[event >> 3] |= bit_of(event);
    }
}

unsigned char svm_kilobot_take(uint8_t event)
{
    uint8_t got;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        got = (uint8_t)(received[event >> 3] & bit_of(event));
        received[event >> 3] &= (uint8_t)~bit_of(event);
    }
    return (unsigned char)(got != 0u);
}

#if SVM_STREAM
/* In the receive interrupt: queue the chunk, or drop it (queue full, or already running a
 * streamed image: nothing more is taken). */
static void queue_chunk(const uint8_t *data)
{
    uint8_t i;
    volatile uint8_t *slot;
    if (from_stream || (uint8_t)(chunk_head - chunk_tail) >= SVM_KILOBOT_CHUNK_SLOTS) {
        return;
    }
    slot = chunk_slot[chunk_head % SVM_KILOBOT_CHUNK_SLOTS];
    for (i = 0; i < SVM_CHUNK_BYTES; i++) {
        slot[i] = data[i];
    }
    chunk_head++;
}
#endif

/* In the IR receive interrupt: the VM's messages set their events' bits (or queue a chunk);
 * the others go to the program's hook. */
uint8_t svm_kilobot_receive(message_t *message, distance_measurement_t *distance)
{
    const svm_kilobot_wire_t *wire;
    uint8_t event;
#if SVM_STREAM
    if (message->type == SVM_MSG_IMAGE_CHUNK) {
        queue_chunk(message->data);
        return 1;
    }
#endif
    if (message->type == NORMAL) {
        /* At most one received event per payload: gen refuses messages that agree on 9 bytes.
         * An Eva directive (docs/proof.md): the table holds one entry per public event, then the end. */
        //@ loop unroll SVM_MAX_EVENTS + 1u;
        for (wire = svm_kilobot_wires; (event = wire_event(wire)) != SVM_KILOBOT_END; wire++) {
            if (SVM_FLASH_BYTE(&wire->received) && flash_compare(message->data, wire->wire, sizeof message->data) == 0) {
                received[event >> 3] |= bit_of(event);
                return 1;
            }
        }
    }
    svm_kilobot_on_message(message, distance);
    return 0;
}

/* The wire of the next pending event after the last one sent (events take turns), or 0. */
static const svm_kilobot_wire_t *next_pending(void)
{
    const svm_kilobot_wire_t *wire, *chosen = 0;
    uint8_t event, later = 0;
    /* An Eva directive (docs/proof.md): the table holds one entry per public event, then the end. */
    //@ loop unroll SVM_MAX_EVENTS + 1u;
    for (wire = svm_kilobot_wires; (event = wire_event(wire)) != SVM_KILOBOT_END; wire++) {
        if (SVM_FLASH_BYTE(&wire->received) || !(pending[event >> 3] & bit_of(event))) {
            continue;
        }
        if (chosen == 0 || (!later && event > outgoing_event)) {
            chosen = wire;
            later = (uint8_t)(event > outgoing_event);
        }
    }
    return chosen;
}

/* In the Timer0 interrupt: the message kilolib sends now, built here. */
message_t *svm_kilobot_transmit(void)
{
    const svm_kilobot_wire_t *wire = next_pending();
    if (wire == 0) {
        return 0;
    }
    outgoing_event = wire_event(wire);
    flash_copy(outgoing.data, wire->wire, sizeof outgoing.data);
    outgoing.type = NORMAL;
    outgoing.crc = message_crc(&outgoing);
    return &outgoing;
}

/* In the same interrupt, after svm_kilobot_transmit's message went out. */
void svm_kilobot_transmitted(void)
{
    pending[outgoing_event >> 3] &= (uint8_t)~bit_of(outgoing_event);
}

#if SVM_STREAM
static uint8_t dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    return svm_kilobot_app_dispatch(machine, from_stream ? own_event[event] : event, op);
}

/* Fill own_event for `image` from this program's events (the compiled-in image's names, while
 * it runs): every event must exist here, with the same kind. */
static int match_events(const svm_vm_t *image)
{
    char event_name[SVM_KILOBOT_NAME_BYTES] = {0};
    uint8_t e, length;
    if (!svm_has_names(image)) {
        return SVM_ERR_NAMES;
    }
    for (e = 0; e < svm_num_events(image); e++) {
        int own;
        length = svm_event_name(image, e, event_name, sizeof event_name);
        if (length >= sizeof event_name - 1u) {
            return SVM_ERR_NAMES;   /* longer than any name of this program */
        }
        own = svm_event_index_n(&vm, event_name, length);
        if (own < 0 || svm_is_controllable(&vm, (uint8_t)own) != svm_is_controllable(image, e)) {
            return SVM_ERR_NAMES;
        }
        own_event[e] = (uint8_t)own;
    }
    return SVM_OK;
}

/* A whole, valid image is in the buffer: check its events on a scratch VM (the running one
 * keeps its logic if this fails), then load it, which resets the VM to its initial states. */
static uint8_t swap(uint16_t *value)
{
    svm_vm_t incoming;
    uint16_t length = svm_stream_length(&stream);
    int result;
    svm_init(&incoming);
    result = svm_load(&incoming, stream_buffer, length);
    if (result == SVM_OK) {
        result = match_events(&incoming);
    }
    if (result == SVM_OK) {
        result = svm_load(&vm, stream_buffer, length);
        from_stream = (uint8_t)(result == SVM_OK);
    }
    *value = result == SVM_OK ? length : (uint16_t)result;
    return result == SVM_OK ? SVM_STREAM_COMPLETE : SVM_STREAM_INVALID;
}

/* Take the oldest queued chunk into `chunk`; 0 when none. */
static uint8_t take_chunk(uint8_t *chunk)
{
    uint8_t i, got = 0;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        if (chunk_tail != chunk_head && !from_stream) {
            for (i = 0; i < SVM_CHUNK_BYTES; i++) {
                chunk[i] = chunk_slot[chunk_tail % SVM_KILOBOT_CHUNK_SLOTS][i];
            }
            chunk_tail++;
            got = 1;
        }
    }
    return got;
}

/* Between two steps: feed the queued chunks to the receiver, swap when one completes, and
 * tell the controller of each change of status. */
static void take_chunks(void)
{
    uint8_t chunk[SVM_CHUNK_BYTES];
    while (take_chunk(chunk)) {
        uint16_t value = 0;
        uint8_t status = svm_stream_feed(&stream, chunk);
        if (status == SVM_STREAM_COMPLETE) {
            status = swap(&value);
        } else if (status == SVM_STREAM_OUT_OF_SEQUENCE) {
            value = chunk[0];
        } else if (status == SVM_STREAM_TOO_LARGE) {
            value = SVM_STREAM_BYTES;
        } else if (status == SVM_STREAM_INVALID) {
            value = stream.error;
        }
        if (status != stream_reported) {
            stream_reported = status;
            svm_kilobot_app_on_stream(status, value);
        }
    }
}
#endif

static uint32_t now(void)
{
    uint32_t ticks;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        ticks = kilo_ticks;
    }
    return ticks;
}

#if SVM_LEARNED
/* The learned policy chooses; its parameters come from the EEPROM store when it holds them. */
static int learn_start(void)
{
    svm_store_avr_eeprom(&store, SVM_KILOBOT_EEPROM_FREE, (uint16_t)SVM_KILOBOT_SLOT_BYTES);
    /* -1: the model needs more than SVM_KILOBOT_THETA */
    return svl_keeper_begin(&keeper, &policy, &vm, vm.seed, theta, SVM_KILOBOT_THETA, words, &store,
                            SVM_KILOBOT_KEEP_EVERY) < 0 ? -1 : SVM_OK;
}

void svm_kilobot_reward(int32_t reward_q16)
{
    (void)svl_keeper_reward(&keeper, reward_q16);
}

const svl_keeper_t *svm_kilobot_keeper(void)
{
    return &keeper;
}
#endif

__attribute__((weak)) void svm_kilobot_after_step(void)
{
}

__attribute__((weak)) void svm_kilobot_on_begin(void)
{
}

__attribute__((weak)) void svm_kilobot_on_message(message_t *message, distance_measurement_t *distance)
{
    (void)message;
    (void)distance;
}

void svm_kilobot_hold(uint8_t hold)
{
    held = hold;
}

/* Options and seed to the VM (applied at its next reset: svm_load's, or the one here once an
 * image runs), and the seed's low byte to kilolib's rand_soft, which the Nadzoru C API draws
 * from on the Kilobot (-DSVM_SCT_RANDOM=rand_soft): so that it differs per robot too. */
void svm_kilobot_set_options(uint8_t options, uint32_t seed)
{
    svm_set_options(&vm, options, seed);
    rand_seed((uint8_t)seed);
    if (vm.image != 0) {
        svm_reset(&vm);
    }
}

#if SVM_KILOBOT_SEED == SVM_KILOBOT_SEED_RAND_HARD
/* Four bytes of rand_hard (noise of the ADC's lowest bit, debiased by kilolib). */
static uint32_t robot_seed(void)
{
    uint32_t seed = 0;
    uint8_t i;
    for (i = 0; i < 4u; i++) {
        seed = (seed << 8) | rand_hard();
    }
    return seed;
}
#else
static uint32_t robot_seed(void)
{
    return SVM_KILOBOT_UID_SEED(kilo_uid);
}
#endif

int svm_kilobot_begin(void)
{
    int result;
    uint32_t seed = robot_seed();
    svm_init(&vm);
#if SVM_STREAM
    svm_stream_init(&stream, stream_buffer, SVM_STREAM_BYTES);
    svm_set_dispatch(&vm, dispatch);
#else
    svm_set_dispatch(&vm, svm_kilobot_app_dispatch);
#endif
    /* svm_kilobot_set_options without its reset: the load below resets with this seed. */
    svm_set_options(&vm, SVM_KILOBOT_OPTIONS, seed);
    rand_seed((uint8_t)seed);
    result = svm_kilobot_app_load(&vm);
#if SVM_LEARNED
    if (result == SVM_OK) {
        result = learn_start();
    }
#endif
    last_step = now();
    svm_kilobot_on_begin();
    return result;
}

uint8_t svm_kilobot_step(void)
{
    uint8_t fired;
#if SVM_STREAM
    take_chunks();
#endif
    fired = svm_step(&vm);
    svm_kilobot_after_step();
    return fired;
}

/* Once per SVM_KILOBOT_TICKS_PER_STEP kilolib ticks, unless held: a step. */
void svm_kilobot_poll(void)
{
    uint32_t ticks = now();
    if (held || (uint32_t)(ticks - last_step) < SVM_KILOBOT_TICKS_PER_STEP) {
        return;
    }
    last_step = ticks;
    (void)svm_kilobot_step();
}
