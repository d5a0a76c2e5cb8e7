/*
 * swarmvm learning (C twin of runtime_py/swarmvm_learn.py; specified in docs/learning.md).
 *
 * 1. svl_classifier: the online linear classifier of learned checks. Features standardised
 *    with a known mean and deviation, f(x) = w.x + b, decide iff f >= 0, bid value f/||w||,
 *    SGD on the modified Huber loss with L2 penalty and scikit-learn's "optimal" step size.
 *    Arithmetic in SVL_REAL: double by default (agrees with the Python twin and scikit-learn
 *    to ~1e-12 on a host); build with -DSVL_REAL=float for single precision (on AVR, double
 *    is float anyway).
 * 2. svl_policy: the VM's `learned` selection policy (SVM_POLICY_LEARNED): a softmax over
 *    integer preferences per (supervisor state, controllable event), REINFORCE with a
 *    baseline. Integer fixed point only, so it makes the same choices as the Python twin for
 *    the same seed and rewards. Plug it in with svm_set_chooser(vm, svl_policy_choose, &p).
 *
 * C99, no heap: the caller owns every buffer. Limits: SVL_MAX_FEATURES (default 8).
 */
#ifndef SWARMVM_LEARN_H
#define SWARMVM_LEARN_H

#include <stdint.h>

#include "swarmvm.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef SVL_REAL
#define SVL_REAL double
#endif
typedef SVL_REAL svl_real;

#ifndef SVL_MAX_FEATURES
#define SVL_MAX_FEATURES 8
#endif

/* ---- online linear classifier ----------------------------------------------------------- */

typedef struct svl_classifier {
    uint8_t n;                          /* number of features */
    svl_real mean[SVL_MAX_FEATURES];
    svl_real scale[SVL_MAX_FEATURES];
    svl_real w[SVL_MAX_FEATURES];       /* weights on standardised features */
    svl_real intercept;
    svl_real alpha;                     /* L2 strength */
    svl_real t0;                        /* step size at update t: 1 / (alpha (t0 + t - 1)) */
    svl_real t;                         /* count of the next update (scikit-learn's t_) */
} svl_classifier_t;

/* Zero weights, t = 1; returns 0, or -1 when n is 0 or above SVL_MAX_FEATURES. */
int svl_classifier_init(svl_classifier_t *c, uint8_t n, const svl_real *mean,
                        const svl_real *scale, svl_real alpha);

/* Train from zero as SGDClassifier.fit(shuffle=False): epochs over the `count` samples
 * (row-major, n values each; labels 1 or 0) until the mean objective fails to improve by `tol`
 * for `patience` epochs in a row (tol < 0: run all max_iter). Returns the epochs run. */
uint16_t svl_classifier_fit(svl_classifier_t *c, const svl_real *samples, const uint8_t *labels,
                            uint16_t count, uint16_t max_iter, svl_real tol, uint8_t patience);

/* One SGD update on one labelled sample (raw features; label 1 positive, 0 negative). */
void svl_classifier_partial_fit(svl_classifier_t *c, const svl_real *x, uint8_t label);

svl_real svl_classifier_decision(const svl_classifier_t *c, const svl_real *x);
uint8_t svl_classifier_decide(const svl_classifier_t *c, const svl_real *x);  /* f >= 0 */
svl_real svl_classifier_bid_value(const svl_classifier_t *c, const svl_real *x); /* f/||w|| */

/* ---- learned selection policy ----------------------------------------------------------- */

#define SVL_POLICY_MAGIC 0x53564C50UL   /* "SVLP", first word of saved parameters */
#define SVL_POLICY_VERSION 1UL
#define SVL_POLICY_HEADER_WORDS 8u      /* magic, version, count, beta, rate, shift, baseline, updates */
#define SVL_Q16(x) ((int32_t)((x) * 65536.0 + ((x) >= 0 ? 0.5 : -0.5)))

typedef struct svl_policy {
    int32_t *theta;                     /* caller's storage: states x controllable events */
    uint16_t num_theta;
    uint8_t width;                      /* number of controllable events */
    uint8_t num_supervisors;
    uint8_t rank[SVM_MAX_EVENTS];       /* column of each controllable event */
    uint16_t inv_temp_q8;               /* 1/temperature, Q8.8 (256 = 1.0) */
    uint16_t rate_q16;                  /* learning rate, Q16 (below 1.0) */
    uint8_t baseline_shift;             /* baseline moves 2^-shift of the way to each reward */
    int32_t baseline;                   /* Q16 */
    uint32_t updates;
    uint32_t moved;                     /* sum of |change| of the preferences (Q16, saturating)
                                         * since the caller last cleared it (not saved) */
    /* the last choice, credited by svl_policy_reward */
    uint8_t pending;                    /* number of alternatives (0: nothing to credit) */
    uint8_t chosen;
    uint16_t rows[SVM_MAX_SUPERVISORS];
    uint8_t ranks[SVM_MAX_EVENTS];
    uint16_t probs[SVM_MAX_EVENTS];     /* Q15 */
} svl_policy_t;

/* Number of int32_t preferences the policy needs for the image loaded in `vm`. */
uint16_t svl_policy_size(const svm_vm_t *vm);

/* Bind to the image loaded in `vm` with `theta` (capacity `cap`, zeroed here). Returns 0, or
 * -1 when cap < svl_policy_size(vm) or baseline_shift >= 32 (a shift the baseline's update
 * cannot make: undefined in C). */
int svl_policy_init(svl_policy_t *p, const svm_vm_t *vm, int32_t *theta, uint16_t cap,
                    uint16_t inv_temp_q8, uint16_t rate_q16, uint8_t baseline_shift);

/* The chooser hook (svm_chooser_fn): ctx is the svl_policy_t. */
uint8_t svl_policy_choose(svm_vm_t *vm, const uint8_t *enabled, uint8_t count, void *ctx);

/* Credit the last choice with a Q16 reward; returns 1, or 0 when there was nothing to credit. */
uint8_t svl_policy_reward(svl_policy_t *p, int32_t reward_q16);

/* exp(-x) in Q15 for x >= 0 in Q16 (the policy's fixed-point exponential). */
uint16_t svl_exp_neg_q15(uint32_t x_q16);

/* Save as a flat array (header, theta, CRC word): returns the words written, 0 if cap is short. */
uint16_t svl_policy_save(const svl_policy_t *p, uint32_t *words, uint16_t cap);

/* Load a saved array; returns 0, or -1 on a wrong magic/version/size or checksum, or values the
 * policy never holds (a shift of 32 or more, a baseline or a preference past its clamp). */
int svl_policy_load(svl_policy_t *p, const uint32_t *words, uint16_t count);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_LEARN_H */
