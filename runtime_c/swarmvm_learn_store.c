/* swarmvm learned policy kept in a two-slot store (swarmvm_learn_store.h). */
#include "swarmvm_learn_store.h"

/* The words as little-endian bytes, in place: byte 4i..4i+3 is word i's own storage. */
static void words_to_bytes(uint32_t *words, uint16_t count)
{
    uint8_t *bytes = (uint8_t *)words;
    uint16_t i;
    for (i = 0; i < count; i++) {
        uint32_t w = words[i];
        bytes[4u * i] = (uint8_t)w;
        bytes[4u * i + 1u] = (uint8_t)(w >> 8);
        bytes[4u * i + 2u] = (uint8_t)(w >> 16);
        bytes[4u * i + 3u] = (uint8_t)(w >> 24);
    }
}

static void bytes_to_words(uint32_t *words, uint16_t count)
{
    const uint8_t *bytes = (const uint8_t *)words;
    uint16_t i;
    for (i = 0; i < count; i++) {
        words[i] = (uint32_t)bytes[4u * i] | ((uint32_t)bytes[4u * i + 1u] << 8)
                   | ((uint32_t)bytes[4u * i + 2u] << 16) | ((uint32_t)bytes[4u * i + 3u] << 24);
    }
}

int svl_keeper_start(svl_keeper_t *k, svl_policy_t *policy, const svm_store_t *store, uint32_t *words,
                     uint16_t cap, uint16_t every, uint32_t epsilon)
{
    int32_t length;
    k->policy = policy;
    k->store = store;
    k->words = words;
    k->cap = cap;
    k->every = every;
    k->epsilon = epsilon;
    k->since = 0;
    k->saves = 0;
    policy->moved = 0;
    length = cap > UINT16_MAX / 4u ? -1 : svm_store_load(store, (uint8_t *)words, (uint16_t)(4u * cap), 0);
    if (length <= 0 || length % 4 != 0) {
        return 0;
    }
    bytes_to_words(words, (uint16_t)(length / 4));
    return svl_policy_load(policy, words, (uint16_t)(length / 4)) == 0;
}

int svl_keeper_begin(svl_keeper_t *k, svl_policy_t *policy, svm_vm_t *vm, uint32_t seed, int32_t *theta,
                     uint16_t theta_cap, uint32_t *words, const svm_store_t *store, uint16_t every)
{
    k->policy = 0;
    if (svl_policy_size(vm) > theta_cap) {
        return -1;
    }
    svm_set_options(vm, (uint8_t)((vm->options & (uint8_t)~SVM_POLICY_MASK) | SVM_POLICY_LEARNED), seed);
    svm_reset(vm);
    (void)svl_policy_init(policy, vm, theta, theta_cap, SVL_KEEPER_INV_TEMP_Q8, SVL_KEEPER_RATE_Q16,
                          SVL_KEEPER_BASELINE_SHIFT);
    svm_set_chooser(vm, svl_policy_choose, policy);
    return svl_keeper_start(k, policy, store, words, (uint16_t)SVL_KEEPER_WORDS(theta_cap), every, SVL_KEEPER_EPSILON);
}

int svl_keeper_save(svl_keeper_t *k)
{
    uint16_t count = k->cap > UINT16_MAX / 4u ? 0u : svl_policy_save(k->policy, k->words, k->cap);
    if (count == 0u) {
        return -1;
    }
    words_to_bytes(k->words, count);
    if (svm_store_save(k->store, (const uint8_t *)k->words, (uint16_t)(4u * count)) != 0) {
        return -1;
    }
    k->since = 0;
    k->saves++;
    k->policy->moved = 0;
    return 0;
}

int svl_keeper_reward(svl_keeper_t *k, int32_t reward_q16)
{
    if (k->policy == 0 || !svl_policy_reward(k->policy, reward_q16)) {
        return 0;
    }
    if (k->since < UINT16_MAX) {
        k->since++;
    }
    if (k->since < k->every || k->policy->moved < k->epsilon) {
        return 0;
    }
    return svl_keeper_save(k) == 0 ? 1 : -1;
}
