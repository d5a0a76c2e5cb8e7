/*
 * swarmvm learning: online linear classifier and learned selection policy.
 * See swarmvm_learn.h; the arithmetic is specified in docs/learning.md and mirrors
 * runtime_py/swarmvm_learn.py operation for operation.
 */
#include "swarmvm_learn.h"

#include <math.h>

/* ===================================================================================== */
/* Online linear classifier                                                               */
/* ===================================================================================== */

/* scikit-learn rescales its weight vector below this scale (1e-9 in double, 1e-6 in float). */
#define SVL_WSCALE_RESET (sizeof(svl_real) >= 8 ? (svl_real)1e-9 : (svl_real)1e-6)
#define SVL_MAX_DLOSS ((svl_real)1e12)

static svl_real svl_sqrt(svl_real x)
{
    return (svl_real)sqrt((double)x);
}

/* Modified Huber loss and its derivative in p, for y in {-1, +1}. */
static svl_real huber_loss(svl_real y, svl_real p)
{
    svl_real z = p * y;
    if (z >= 1) {
        return 0;
    }
    if (z >= -1) {
        return (1 - z) * (1 - z);
    }
    return -4 * z;
}

static svl_real huber_gradient(svl_real y, svl_real p)
{
    svl_real z = p * y;
    if (z >= 1) {
        return 0;
    }
    if (z >= -1) {
        return 2 * (1 - z) * -y;
    }
    return -4 * y;
}

int svl_classifier_init(svl_classifier_t *c, uint8_t n, const svl_real *mean,
                        const svl_real *scale, svl_real alpha)
{
    uint8_t i;
    svl_real typw, gradient;
    if (n == 0 || n > SVL_MAX_FEATURES) {
        return -1;
    }
    c->n = n;
    for (i = 0; i < n; i++) {
        c->mean[i] = mean[i];
        c->scale[i] = scale[i];
        c->w[i] = 0;
    }
    c->intercept = 0;
    c->alpha = alpha;
    c->t = 1;
    /* Bottou's heuristic as scikit-learn applies it: eta0 = typw / max(1, dloss(1, -typw)). */
    typw = svl_sqrt(1 / svl_sqrt(alpha));
    gradient = huber_gradient(1, -typw);
    c->t0 = 1 / (typw / (gradient > 1 ? gradient : 1) * alpha);
    return 0;
}

static void standardise(const svl_classifier_t *c, const svl_real *x, svl_real *out)
{
    uint8_t i;
    for (i = 0; i < c->n; i++) {
        out[i] = (x[i] - c->mean[i]) / c->scale[i];
    }
}

static svl_real dot(const svl_real *v, const svl_real *x, uint8_t n, svl_real wscale)
{
    svl_real total = 0;
    uint8_t i;
    for (i = 0; i < n; i++) {
        total += v[i] * x[i];
    }
    return total * wscale;
}

/* scikit-learn's plain SGD loop for this loss and penalty (dense data, no averaging): weights
 * kept as wscale * w during the call, folded back at the end. `samples` are raw features. */
static uint16_t sgd(svl_classifier_t *c, const svl_real *samples, const uint8_t *labels,
                    uint16_t count, uint16_t max_iter, svl_real tol, uint8_t patience)
{
    svl_real x[SVL_MAX_FEATURES];
    svl_real wscale = 1, sq_norm = 0, t = c->t, best = 0;
    uint8_t have_best = 0, no_improvement = 0, i;
    uint16_t epoch = 0, k;
    for (i = 0; i < c->n; i++) {
        sq_norm += c->w[i] * c->w[i];
    }
    while (epoch < max_iter) {
        svl_real objective = 0, mean_objective;
        epoch++;
        for (k = 0; k < count; k++) {
            svl_real y = labels[k] ? 1 : -1;
            svl_real p, eta, dloss, update, shrink, norm;
            standardise(c, samples + (uint32_t)k * c->n, x);
            p = dot(c->w, x, c->n, wscale) + c->intercept;
            eta = 1 / (c->alpha * (c->t0 + t - 1));
            norm = svl_sqrt(sq_norm);
            objective += huber_loss(y, p);
            objective += c->alpha * ((svl_real)0.5 * (norm * norm));
            dloss = huber_gradient(y, p);
            dloss = dloss < -SVL_MAX_DLOSS ? -SVL_MAX_DLOSS : dloss > SVL_MAX_DLOSS ? SVL_MAX_DLOSS : dloss;
            update = -eta * dloss;
            shrink = 1 - eta * c->alpha;
            shrink = shrink > 0 ? shrink : 0;
            wscale *= shrink;
            sq_norm *= shrink * shrink;
            if (wscale < SVL_WSCALE_RESET) {
                for (i = 0; i < c->n; i++) {
                    c->w[i] *= wscale;
                }
                wscale = 1;
            }
            if (update != 0) {
                svl_real step = update / wscale, acc = 0;
                for (i = 0; i < c->n; i++) {
                    c->w[i] += x[i] * step;
                    acc += c->w[i] * c->w[i];
                }
                sq_norm = acc * (wscale * wscale);
                c->intercept += update;
            }
            t += 1;
        }
        mean_objective = objective / count;
        if (tol >= 0 && have_best && mean_objective > best - tol) {
            no_improvement++;
        } else {
            no_improvement = 0;
        }
        if (!have_best || mean_objective < best) {
            best = mean_objective;
            have_best = 1;
        }
        if (no_improvement >= patience) {
            break;
        }
    }
    for (i = 0; i < c->n; i++) {
        c->w[i] *= wscale;
    }
    return epoch;
}

uint16_t svl_classifier_fit(svl_classifier_t *c, const svl_real *samples, const uint8_t *labels,
                            uint16_t count, uint16_t max_iter, svl_real tol, uint8_t patience)
{
    uint8_t i;
    uint16_t epochs;
    for (i = 0; i < c->n; i++) {
        c->w[i] = 0;
    }
    c->intercept = 0;
    c->t = 1;
    if (count == 0) {
        return 0;
    }
    epochs = sgd(c, samples, labels, count, max_iter, tol, patience);
    c->t += (svl_real)epochs * count;
    return epochs;
}

void svl_classifier_partial_fit(svl_classifier_t *c, const svl_real *x, uint8_t label)
{
    sgd(c, x, &label, 1, 1, -1, 1);
    c->t += 1;
}

svl_real svl_classifier_decision(const svl_classifier_t *c, const svl_real *x)
{
    svl_real z[SVL_MAX_FEATURES];
    standardise(c, x, z);
    return dot(c->w, z, c->n, 1) + c->intercept;
}

uint8_t svl_classifier_decide(const svl_classifier_t *c, const svl_real *x)
{
    return svl_classifier_decision(c, x) >= 0;
}

svl_real svl_classifier_bid_value(const svl_classifier_t *c, const svl_real *x)
{
    svl_real sq = 0, norm;
    uint8_t i;
    for (i = 0; i < c->n; i++) {
        sq += c->w[i] * c->w[i];
    }
    norm = svl_sqrt(sq);
    return norm > 0 ? svl_classifier_decision(c, x) / norm : 0;
}

/* ===================================================================================== */
/* Learned selection policy (integer fixed point, bit-identical with the Python twin)     */
/* ===================================================================================== */

#define THETA_LIMIT (32L << 16)
#define REWARD_LIMIT (1L << 24)
#define ADVANTAGE_LIMIT ((1L << 22) - 1)
#define DIFF_LIMIT 0x7FFFUL
#define EXP_CUTOFF (16UL << 16)
#define LOG2E_Q14 23637UL
#define Q15_ONE ((int32_t)SVM_Q15_ONE)   /* swarmvm_format.h's, signed for the updates below */

/* round(32768 * 2^(-j/16)), j = 0..16; in flash on AVR */
#if defined(__AVR__)
#define EXP2(j) pgm_read_word(&exp2_table[j])
#else
#define EXP2(j) exp2_table[j]
#endif
static const uint16_t exp2_table[17] SVM_PROGMEM = {
    32768, 31379, 30048, 28774, 27554, 26386, 25268, 24196, 23170,
    22188, 21247, 20347, 19484, 18658, 17867, 17109, 16384
};

/* Floor division by 2^bits of a signed value, without relying on how >> treats negatives. */
static int32_t floor_shift(int32_t value, uint8_t bits)
{
    return value >= 0 ? (int32_t)((uint32_t)value >> bits) : (int32_t)~((uint32_t)~value >> bits);
}

static int32_t clamp(int32_t value, int32_t limit)
{
    return value < -limit ? -limit : value > limit ? limit : value;
}

uint16_t svl_exp_neg_q15(uint32_t x)
{
    uint32_t y, whole, frac, j, r;
    if (x >= EXP_CUTOFF) {
        return 0;
    }
    y = (uint32_t)(((x >> 4) * LOG2E_Q14) >> 10);
    whole = y >> 16;
    frac = y & 0xFFFFUL;
    j = frac >> 12;
    r = frac & 0xFFFUL;
    return (uint16_t)((EXP2(j) - ((((uint32_t)EXP2(j) - EXP2(j + 1)) * r) >> 12)) >> whole);
}

uint16_t svl_policy_size(const svm_vm_t *vm)
{
    uint8_t e, width = 0;
    for (e = 0; e < svm_num_events(vm); e++) {
        width = (uint8_t)(width + (svm_is_controllable(vm, e) ? 1u : 0u));
    }
    return (uint16_t)(svm_num_states(vm) * width);
}

int svl_policy_init(svl_policy_t *p, const svm_vm_t *vm, int32_t *theta, uint16_t cap,
                    uint16_t inv_temp_q8, uint16_t rate_q16, uint8_t baseline_shift)
{
    uint8_t e;
    uint16_t i, size = svl_policy_size(vm);
    if (cap < size || baseline_shift >= 32u) {     /* floor_shift's shift is below 32 */
        return -1;
    }
    p->theta = theta;
    p->num_theta = size;
    p->width = 0;
    for (e = 0; e < svm_num_events(vm); e++) {
        p->rank[e] = svm_is_controllable(vm, e) ? p->width++ : 0xFF;
    }
    p->num_supervisors = svm_num_supervisors(vm);
    for (i = 0; i < size; i++) {
        theta[i] = 0;
    }
    p->inv_temp_q8 = inv_temp_q8;
    p->rate_q16 = rate_q16;
    p->baseline_shift = baseline_shift;
    p->baseline = 0;
    p->updates = 0;
    p->moved = 0;
    p->pending = 0;
    return 0;
}

uint8_t svl_policy_choose(svm_vm_t *vm, const uint8_t *enabled, uint8_t count, void *ctx)
{
    svl_policy_t *p = (svl_policy_t *)ctx;
    int32_t prefs[SVM_MAX_EVENTS];
    uint16_t weights[SVM_MAX_EVENTS];
    uint8_t events[SVM_MAX_EVENTS];
    int32_t top = 0;
    uint32_t total = 0, pick;
    uint8_t i, s, m = svm_mask_bytes(vm);
    for (i = 0; i < count; i++) {
        events[i] = svm_mask_nth(enabled, m, i);
    }
    p->pending = 0;
    if (count == 1) {
        return events[0];
    }
    for (s = 0; s < p->num_supervisors; s++) {
        p->rows[s] = (uint16_t)(svm_global_state(vm, s) * p->width);
    }
    for (i = 0; i < count; i++) {
        int32_t h = 0;
        p->ranks[i] = p->rank[events[i]];
        for (s = 0; s < p->num_supervisors; s++) {
            h += p->theta[p->rows[s] + p->ranks[i]];
        }
        prefs[i] = h;
        if (i == 0 || h > top) {
            top = h;
        }
    }
    for (i = 0; i < count; i++) {
        uint32_t gap = (uint32_t)floor_shift(top - prefs[i], 8);
        weights[i] = svl_exp_neg_q15((gap < DIFF_LIMIT ? gap : DIFF_LIMIT) * p->inv_temp_q8);
        total += weights[i];
    }
    pick = svm_random(vm) % total;
    for (i = 0; pick >= weights[i]; i++) {
        pick -= weights[i];
    }
    p->chosen = i;
    for (s = 0; s < count; s++) {
        p->probs[s] = (uint16_t)(((uint32_t)weights[s] * (uint32_t)Q15_ONE) / total);
    }
    p->pending = count;
    /* i < count: the weights are positive and sum to total > pick. */
    return events[i];  // cppcheck-suppress uninitvar
}

uint8_t svl_policy_reward(svl_policy_t *p, int32_t reward)
{
    int32_t advantage, step9;
    uint8_t i, s;
    if (p->pending == 0) {
        return 0;
    }
    reward = clamp(reward, REWARD_LIMIT);
    advantage = clamp(reward - p->baseline, ADVANTAGE_LIMIT);
    p->baseline += floor_shift(reward - p->baseline, p->baseline_shift);
    step9 = floor_shift(floor_shift(advantage, 8) * (int32_t)p->rate_q16, 15);
    for (i = 0; i < p->pending; i++) {
        int32_t diff = (int32_t)(i == p->chosen ? Q15_ONE : 0) - (int32_t)p->probs[i];
        int32_t delta = floor_shift(step9 * diff, 8);
        for (s = 0; s < p->num_supervisors; s++) {
            int32_t *cell = &p->theta[p->rows[s] + p->ranks[i]];
            int32_t before = *cell;
            uint32_t change;
            *cell = clamp(*cell + delta, THETA_LIMIT);
            change = (uint32_t)(*cell >= before ? *cell - before : before - *cell);
            p->moved = p->moved > UINT32_MAX - change ? UINT32_MAX : p->moved + change;
        }
    }
    p->updates++;
    p->pending = 0;
    return 1;
}

/* CRC-16/MCRF4XX (the image checksum) over the little-endian bytes of 32-bit words. */
static uint16_t crc_words(const uint32_t *words, uint16_t count)
{
    uint16_t crc = SVM_CRC16_INIT, i;
    uint8_t b;
    for (i = 0; i < count; i++) {
        for (b = 0; b < 4; b++) {
            crc = svm_crc16_update(crc, (uint8_t)(words[i] >> (8 * b)));
        }
    }
    return crc;
}

uint16_t svl_policy_save(const svl_policy_t *p, uint32_t *words, uint16_t cap)
{
    uint16_t i, total = (uint16_t)(SVL_POLICY_HEADER_WORDS + p->num_theta + 1);
    if (cap < total) {
        return 0;
    }
    words[0] = SVL_POLICY_MAGIC;
    words[1] = SVL_POLICY_VERSION;
    words[2] = p->num_theta;
    words[3] = p->inv_temp_q8;
    words[4] = p->rate_q16;
    words[5] = p->baseline_shift;
    words[6] = (uint32_t)p->baseline;
    words[7] = p->updates;
    for (i = 0; i < p->num_theta; i++) {
        words[SVL_POLICY_HEADER_WORDS + i] = (uint32_t)p->theta[i];
    }
    words[total - 1] = crc_words(words, (uint16_t)(total - 1));
    return total;
}

/* Whether a saved word, as the int32_t it holds, lies within +-limit. */
static int within(uint32_t word, int32_t limit)
{
    int32_t value = (int32_t)word;
    return value >= -limit && value <= limit;
}

/* Whether the saved values are ones the policy can hold: a checksum that matches does not make
 * an array this policy's (another writer, or a corruption that keeps it), and a shift of 32 or
 * more, or a baseline or preference past its clamp, would reach an undefined shift or a signed
 * overflow in the step (docs/proof.md, "Real defects"). */
static int plausible(const uint32_t *words, uint16_t num_theta)
{
    uint16_t i;
    if (words[3] > 0xFFFFu || words[4] > 0xFFFFu || words[5] >= 32u || !within(words[6], REWARD_LIMIT)) {
        return 0;
    }
    for (i = 0; i < num_theta; i++) {
        if (!within(words[SVL_POLICY_HEADER_WORDS + i], THETA_LIMIT)) {
            return 0;
        }
    }
    return 1;
}

int svl_policy_load(svl_policy_t *p, const uint32_t *words, uint16_t count)
{
    uint16_t i;
    if (count < SVL_POLICY_HEADER_WORDS + 1 || words[0] != SVL_POLICY_MAGIC
        || words[1] != SVL_POLICY_VERSION || words[2] != p->num_theta
        || count != SVL_POLICY_HEADER_WORDS + p->num_theta + 1
        || words[count - 1] != crc_words(words, (uint16_t)(count - 1)) || !plausible(words, p->num_theta)) {
        return -1;
    }
    p->inv_temp_q8 = (uint16_t)words[3];
    p->rate_q16 = (uint16_t)words[4];
    p->baseline_shift = (uint8_t)words[5];
    p->baseline = (int32_t)words[6];
    p->updates = words[7];
    /* The preferences are within THETA_LIMIT (plausible): clamp() changes none of them, and makes
     * the bound the step's sums rely on evident to Eva (docs/proof.md). */
    for (i = 0; i < p->num_theta; i++) {
        p->theta[i] = clamp((int32_t)words[SVL_POLICY_HEADER_WORDS + i], THETA_LIMIT);
    }
    p->pending = 0;
    return 0;
}
