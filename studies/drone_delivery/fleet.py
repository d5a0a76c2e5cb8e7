"""The fleet: battery health, each drone's bidding policy and VM, and the policies mirrored into
NumPy arrays so that a decision for every drone (or every pending order) is one array expression.

The NumPy decision function performs exactly the floating-point operations of
swarmvm_learn.LinearClassifier.decision_function (standardise, then ((w0 x0 + w1 x1) + w2 x2) + b),
so the fleet-wide answer and the VM's learned check never disagree."""

from __future__ import annotations

import numpy as np

from .controller import DroneLogic, linear_classifier_class
from .energy import NEVER, charged, keep_table, keep_table_negated, measure_level
from .features import MEAN, SCALE, SEED_LABELS, SEED_POINTS
from .params import Params

LEVELS = 1000                           # SoC is read in 0.1 % steps: levels 0..1000


def linear_scores(weights, intercept, distance, mass, soc):
    """f = ((w0 d~ + w1 m~) + w2 s~) + b, in LinearClassifier's order of operations; ``weights``
    (..., 3) and ``intercept`` (...) broadcast against the features."""
    weights = np.asarray(weights)
    dz = (np.asarray(distance, dtype=float) - MEAN[0]) / SCALE[0]
    mz = (np.asarray(mass, dtype=float) - MEAN[1]) / SCALE[1]
    sz = (np.asarray(soc, dtype=float) - MEAN[2]) / SCALE[2]
    return ((weights[..., 0] * dz + weights[..., 1] * mz) + weights[..., 2] * sz) + intercept


def confidence(scores, norm):
    """The bid value f / ||w|| (0 where w = 0)."""
    return np.where(norm > 0.0, scores / np.where(norm > 0.0, norm, 1.0), 0.0)


def weight_norm(weights):
    """||w||, the intercept excluded, summed in LinearClassifier's order."""
    weights = np.asarray(weights)
    return np.sqrt((weights[..., 0] * weights[..., 0] + weights[..., 1] * weights[..., 1]) + weights[..., 2] * weights[..., 2])


class ThresholdPolicy:
    """The baseline's capability check: yes iff the measured SoC reaches the threshold. It does
    not learn (``partial_fit`` is a no-op) but answers the VM's check like a classifier."""

    def __init__(self, threshold_pct: float) -> None:
        self.threshold_pct = threshold_pct

    def decide(self, features) -> bool:
        return features[2] >= self.threshold_pct

    def partial_fit(self, features, label) -> None:
        """The baseline does not learn."""


def initial_classifier(params: Params, rng: np.random.Generator):
    """A classifier after the initial fit on the two assumed points, for ``init_epochs`` epochs
    each in a random order (the published runs shuffle: the intercept's sign varies)."""
    classifier = linear_classifier_class()(MEAN, SCALE, alpha=params.alpha)
    order = [int(k) for _ in range(params.init_epochs) for k in rng.permutation(2)]
    if order:                   # --init-epochs 0: no initial fit, the policy starts at zero
        classifier.fit([SEED_POINTS[k] for k in order], [SEED_LABELS[k] for k in order], max_iter=1, tol=None)
    return classifier


class Fleet:
    """Drones 0..S-1: health, policies, VMs and the NumPy mirror of the policies."""

    def __init__(self, params: Params, rng: np.random.Generator) -> None:
        self.params = params
        self.size = params.drones
        self.soh = rng.uniform(params.soh_min, params.soh_max, self.size)
        self.learning = params.rule != "threshold"
        if self.learning:
            self.policies = [initial_classifier(params, rng) for _ in range(self.size)]
        else:
            self.policies = [ThresholdPolicy(params.threshold_pct) for _ in range(self.size)]
        self.weights = np.zeros((self.size, 3))
        self.intercept = np.zeros(self.size)
        self.norm = np.zeros(self.size)
        for drone in range(self.size):
            self.sync(drone)
        self.new_logic()

    def new_logic(self) -> None:
        """Fresh VMs (at the supervisor's initial state) around the current policies."""
        self.logic = [DroneLogic(policy, seed=drone + 1) for drone, policy in enumerate(self.policies)]

    def sync(self, drone: int) -> None:
        """Copy a drone's classifier into the arrays (after it learned)."""
        if self.learning:
            policy = self.policies[drone]
            self.weights[drone] = policy.weights
            self.intercept[drone] = policy.intercept
            self.norm[drone] = weight_norm(self.weights[drone])

    def learn(self, drone: int, features, delivered: bool) -> None:
        self.logic[drone].learn(features, delivered)
        self.sync(drone)

    # -- decisions ----------------------------------------------------------------------------------
    def scores(self, drones, distance, mass, soc):
        """f(d, m, SoC) (learning) or SoC - threshold (baseline); >= 0 means bid. Broadcasts."""
        soc = np.asarray(soc, dtype=float)
        if not self.learning:
            return np.broadcast_to(soc - self.params.threshold_pct, np.broadcast(soc, np.asarray(distance)).shape)
        return linear_scores(self.weights[drones], self.intercept[drones], distance, mass, soc)

    def bid_values(self, drones, scores, soc):
        """f / ||w|| (0 if w = 0), or the SoC for the baseline."""
        if not self.learning:
            return np.asarray(soc, dtype=float)
        return confidence(scores, self.norm[drones])

    def rising(self, drones) -> np.ndarray:
        """Drones whose decision can only turn from no to yes as their SoC rises (w_SoC > 0, or
        the baseline); for the others it can only turn from yes to no."""
        if not self.learning:
            return np.ones(np.shape(drones), dtype=bool)
        return self.weights[drones][..., 2] > 0.0

    def crossing_level(self, drones, distance, mass) -> np.ndarray:
        """Where the decision flips as the SoC level k (SoC = k/10, 0..1000) rises: for
        :meth:`rising` drones the first level with f >= 0, for the others the first with f < 0;
        LEVELS + 1 if none. Estimated from the linear function, corrected with the exact one."""
        rising = self.rising(drones)
        if self.learning:
            rest = self.scores(drones, distance, mass, MEAN[2])       # f at SoC = mean: no SoC term
            w2 = self.weights[drones][..., 2]
            estimate = MEAN[2] - SCALE[2] * rest / np.where(w2 != 0.0, w2, np.inf)
        else:
            estimate = np.full(np.broadcast(np.asarray(drones), np.asarray(distance)).shape, self.params.threshold_pct)
        level = np.clip(np.ceil(estimate * 10.0), 0, LEVELS + 1).astype(np.int64)

        def crossed(k):
            return (self.scores(drones, distance, mass, k / 10.0) >= 0.0) == rising

        while True:
            up = (level <= LEVELS) & ~crossed(level)
            down = ~up & (level > 0) & crossed(level - 1)
            if not (up.any() or down.any()):
                return level
            level = level + up - down

    def bid_window(self, params: Params, drones, land_tick, land_soc, distance, mass):
        """The ticks [start, stop) during which each drone, charging since ``land_tick`` from
        ``land_soc``, would bid on the order (start = NEVER: not at any charge)."""
        level = self.crossing_level(drones, distance, mass)
        table = keep_table(params.charge_keep)
        deficit = 100.0 - np.asarray(land_soc, dtype=float)
        # measure(100 - deficit * KEEP[n]) >= level/10 about when KEEP[n] <= (100 - (level - .5)/10) / deficit
        target = (100.0 - (level - 0.5) / 10.0) / np.where(deficit > 0.0, deficit, 1.0)
        ticks = np.minimum(np.searchsorted(keep_table_negated(params.charge_keep), -target), len(table) - 1).astype(np.int64)
        ticks = np.where(deficit > 0.0, ticks, 0)                # a full battery stays full
        possible = level <= LEVELS

        def reached(n):
            return measure_level(charged(params, land_soc, n)) >= level

        while True:
            up = possible & ~reached(ticks) & (ticks < len(table) - 1)
            down = possible & ~up & (ticks > 0) & reached(ticks - 1)
            if not (up.any() or down.any()):
                break
            ticks = ticks + up - down
        land_tick = np.asarray(land_tick)
        crossing = np.where(possible & reached(ticks), land_tick + ticks, NEVER)
        rising = self.rising(drones)
        start = np.where(rising, crossing, np.where(crossing > land_tick, land_tick, NEVER))
        stop = np.where(rising, NEVER, crossing)
        return np.broadcast_to(start, level.shape), np.broadcast_to(stop, level.shape)

    def reservation_values(self, drones, distance, mass, soc) -> np.ndarray:
        """Forecast: the time (s) a drone expects to need to charge to the SoC at which it would
        bid, by the linear estimate of a full charge taking C / (P_c gamma_c)."""
        if self.learning:
            rest = self.scores(drones, distance, mass, MEAN[2])       # f at SoC = mean: w.x~ + b without the SoC term
            needed = MEAN[2] - SCALE[2] * rest / self.weights[drones][..., 2]
        else:
            needed = np.full(np.shape(drones), self.params.threshold_pct)
        return np.maximum(needed - soc, 0.0) / 100.0 * self.params.full_charge_s
