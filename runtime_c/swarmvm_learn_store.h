/*
 * swarmvm learned policy kept across resets and power cuts: svl_policy_t (swarmvm_learn.h)
 * saved to and restored from a two-slot store (swarmvm_store.h). One implementation for every
 * C target; a robot's runtime binds the store to its medium (Kilobot: EEPROM; CapBot: flash)
 * and calls the three functions below.
 *
 * Start-up: svl_keeper_start loads the newest valid record into the policy, which the caller
 * has just initialised with its initial parameters; with no valid record (never saved, both
 * slots damaged, or saved for another model: size or checksum differ) those stay.
 *
 * Cadence: a save costs wear and time (ATmega328P EEPROM: 100,000 writes per byte, 3.3 ms per
 * byte, so a forager's 160-byte record holds the Kilobot's loop for about 0.5 s; nRF52840
 * flash: 10,000 erases per page, one page erased per save and slot). svl_keeper_reward saves
 * after `every` rewards *and* only when the preferences moved by at least `epsilon` in all
 * (the sum of |change|, Q16) since the last save: at most one save per `every` rewards, and
 * none while nothing is learned (a converged policy whose rewards match its baseline, a robot
 * that gets no rewards). With the two slots alternating, each slot is written every second
 * save. What is learned after the last save is lost at a reset: up to `every` rewards' worth.
 */
#ifndef SWARMVM_LEARN_STORE_H
#define SWARMVM_LEARN_STORE_H

#include <stdint.h>

#include "swarmvm_learn.h"
#include "swarmvm_store.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Words and bytes of a saved policy with `theta` preferences (svl_policy_save's words). */
#define SVL_KEEPER_WORDS(theta) (SVL_POLICY_HEADER_WORDS + (theta) + 1u)
#define SVL_KEEPER_RECORD_BYTES(theta) (4u * SVL_KEEPER_WORDS(theta))

/* The policy's settings a robot starts from (docs/learning.md): temperature 1, rate 0.1,
 * baseline 1/16; and the save threshold: the preferences moved by 1.0 in all. */
#ifndef SVL_KEEPER_INV_TEMP_Q8
#define SVL_KEEPER_INV_TEMP_Q8 256u
#endif
#ifndef SVL_KEEPER_RATE_Q16
#define SVL_KEEPER_RATE_Q16 6554u
#endif
#ifndef SVL_KEEPER_BASELINE_SHIFT
#define SVL_KEEPER_BASELINE_SHIFT 4u
#endif
#ifndef SVL_KEEPER_EPSILON
#define SVL_KEEPER_EPSILON 65536UL
#endif

typedef struct svl_keeper {
    svl_policy_t *policy;
    const svm_store_t *store;
    uint32_t *words;            /* caller's buffer: SVL_POLICY_HEADER_WORDS + num_theta + 1 words */
    uint16_t cap;               /* its capacity, in words */
    uint16_t every;             /* rewards between two saves, at least */
    uint32_t epsilon;           /* summed |change| of the preferences (Q16) a save needs */
    uint16_t since;             /* rewards since the last save (or the start) */
    uint32_t saves;             /* saves done since the start */
} svl_keeper_t;

/* Bind `policy` (initialised, with its initial parameters) to `store`, and load the newest
 * valid record into it: 1 when one was loaded, 0 when the initial parameters stay. */
int svl_keeper_start(svl_keeper_t *k, svl_policy_t *policy, const svm_store_t *store, uint32_t *words,
                     uint16_t cap, uint16_t every, uint32_t epsilon);

/* A robot's start-up, shared by the C targets: the learned policy chooses in `vm` (loaded;
 * reset here with `seed`), starting from the settings above and all preferences 0, then from
 * the store's newest valid record when there is one; `theta` holds `theta_cap` preferences,
 * `words` SVL_KEEPER_WORDS(theta_cap). Saves every `every` rewards (svl_keeper_reward).
 * Returns 1 (record loaded), 0 (initial parameters), or -1 when the model needs more than
 * theta_cap (the VM keeps its previous policy then, and rewards are ignored). */
int svl_keeper_begin(svl_keeper_t *k, svl_policy_t *policy, svm_vm_t *vm, uint32_t seed, int32_t *theta,
                     uint16_t theta_cap, uint32_t *words, const svm_store_t *store, uint16_t every);

/* svl_policy_reward, then a save when the cadence says so: 1 when it saved, 0 when not, -1
 * when the save failed (the store keeps the previous record; the next reward tries again). */
int svl_keeper_reward(svl_keeper_t *k, int32_t reward_q16);

/* Save now (e.g. before a planned shutdown): 0, or -1. */
int svl_keeper_save(svl_keeper_t *k);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_LEARN_STORE_H */
