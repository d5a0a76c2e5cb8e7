"""What a trial measures (the seed's Figures 16-20): deliveries and their times, aborted
attempts, pending orders and backlog age by arrival week, decision accuracy every week against
the ground truth, and the fleet's final policies (for the SoH-of-winner maps)."""

from __future__ import annotations

import dataclasses

import numpy as np

from .auction import winners
from .energy import delivers, measure
from .fleet import Fleet, confidence, linear_scores, weight_norm
from .params import Params
from .world import LOST


class AccuracyProbe:
    """Per drone, the share of ``accuracy_samples`` random (d, m, SoC) on which its bidding
    decision matches the ground truth (its true health and the energy model). The samples are
    drawn once per trial, d ~ U(d_min, d_max), m ~ U(m_min, m_max), SoC ~ U(0, 100)."""

    def __init__(self, params: Params, fleet: Fleet, rng: np.random.Generator) -> None:
        shape = (fleet.size, params.accuracy_samples)
        self.fleet = fleet
        self.distance = rng.uniform(params.d_min_m, params.d_max_m, shape)
        self.mass = rng.uniform(params.m_min_kg, params.m_max_kg, shape)
        soc = rng.uniform(0.0, 100.0, shape)
        self.readings = measure(soc)
        self.truth = delivers(params, self.distance, self.mass, soc, fleet.soh[:, None])

    def __call__(self) -> np.ndarray:
        drones = np.arange(self.fleet.size)[:, None]
        yes = self.fleet.scores(drones, self.distance, self.mass, self.readings) >= 0.0
        return (yes == self.truth).mean(axis=1)


@dataclasses.dataclass
class Result:
    """One trial's outcome; :meth:`summary` is the JSON of ``swarmvm sim uav --json``."""

    params: Params
    arrival: np.ndarray            # tick of every order
    delivered_tick: np.ndarray     # -1: not delivered
    adverts: int
    takeoffs: int
    aborts: int
    losses: int
    reservations: int
    accuracy: np.ndarray           # weeks + 1 x drones
    soh: np.ndarray
    weights: np.ndarray            # final policies (drones x 3, and intercepts)
    intercept: np.ndarray
    lost: np.ndarray
    vm_states: list
    seconds: float                 # wall time of the trial
    cpu_seconds: float             # CPU time of this process (one core)

    @classmethod
    def collect(cls, params: Params, world, accuracy: list, seconds: float, cpu_seconds: float) -> "Result":
        fleet = world.fleet
        return cls(params, world.orders.tick, world.delivered_tick.copy(), world.adverts, world.takeoffs,
                   world.aborts, world.losses, world.reservations,
                   np.array(accuracy).reshape(len(accuracy), fleet.size), fleet.soh.copy(), fleet.weights.copy(),
                   fleet.intercept.copy(), world.phase == LOST, [logic.state for logic in fleet.logic], seconds, cpu_seconds)

    @property
    def delivery_min(self) -> np.ndarray:
        done = self.delivered_tick >= 0
        return (self.delivered_tick[done] - self.arrival[done]) / 60.0

    def by_arrival_week(self, values: np.ndarray) -> list:
        """Sum of ``values`` over undelivered orders, per arrival week."""
        weeks = self.arrival // self.params.week_s
        waiting = self.delivered_tick < 0
        return [float(values[waiting & (weeks == w)].sum()) for w in range(self.params.weeks)]

    def summary(self) -> dict:
        times = self.delivery_min
        waiting = self.delivered_tick < 0
        age_h = (self.params.horizon - self.arrival) / 3600.0
        return dict(
            orders=int(len(self.arrival)), delivered=int((~waiting).sum()), pending=int(waiting.sum()),
            aborted=self.aborts, takeoffs=self.takeoffs, advertisements=self.adverts, lost=self.losses,
            reservations=self.reservations,
            median_delivery_min=float(np.median(times)) if len(times) else None,
            mean_delivery_min=float(times.mean()) if len(times) else None,
            accuracy_by_week=[float(a) for a in self.accuracy.mean(axis=1)],
            pending_by_week=[int(v) for v in self.by_arrival_week(np.ones(len(self.arrival)))],
            backlog_age_h_by_week=self.by_arrival_week(age_h),
            seconds=round(self.seconds, 3), cpu_seconds=round(self.cpu_seconds, 3))


def winner_soh_map(soh, weights, intercept, socs, distances, masses, rule="least-confident"):
    """Figure 18: the SoH of the drone the rule would deploy for each (SoC, d, m), NaN if no
    drone bids; all drones at the same SoC, with their final policies."""
    soc, d, m = (v.ravel() for v in np.meshgrid(socs, distances, masses, indexing="ij"))
    weights = np.asarray(weights)
    scores = linear_scores(weights[:, None, :], np.asarray(intercept)[:, None], d, m, soc)
    won = winners(confidence(scores, weight_norm(weights)[:, None]), scores >= 0.0, rule)
    result = np.where(won >= 0, np.asarray(soh)[np.maximum(won, 0)], np.nan)
    return result.reshape(len(socs), len(distances), len(masses))
