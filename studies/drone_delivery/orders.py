"""Order arrival (equation 16) as the published runs drew it: all orders drawn at the start,
exponential gaps of mean tau rounded up to whole ticks (at most one order per tick, the first at
tick 0); distance uniform over the *area* of the annulus d_min..d_max (design/STUDIES.md: the
text says uniform in distance); mass uniform."""

from __future__ import annotations

import dataclasses

import numpy as np

from .params import Params


@dataclasses.dataclass
class Orders:
    tick: np.ndarray           # arrival tick, increasing
    distance: np.ndarray       # m
    mass: np.ndarray           # kg

    def __len__(self) -> int:
        return len(self.tick)


def draw_orders(params: Params, rng: np.random.Generator, horizon: int) -> Orders:
    """Every order arriving before ``horizon``."""
    mean = params.tau_min * 60.0
    chunk = int(min(1.2 * horizon / mean, horizon)) + 16     # at most one order a tick
    gaps = [np.zeros(0, dtype=np.int64)]
    total = 0
    while total < horizon:
        # A gap is at least a tick, and at most the horizon: a longer one ends the draw as well, and
        # would not fit the integer ticks (a tau of 1e300 minutes).
        more = np.clip(np.ceil(rng.exponential(mean, chunk)), 1, max(horizon, 1)).astype(np.int64)
        gaps.append(more)
        total += int(more.sum())
    ticks = np.concatenate([[0], np.cumsum(np.concatenate(gaps))])
    ticks = ticks[ticks < horizon]
    count = len(ticks)
    distance = np.sqrt(rng.uniform(params.d_min_m ** 2, params.d_max_m ** 2, count))
    mass = rng.uniform(params.m_min_kg, params.m_max_kg, count)
    return Orders(ticks, distance, mass)

