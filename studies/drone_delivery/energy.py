"""The energy model (equations 13-15) as the simulator evaluates it, shared by both engines so
that they compute every state of charge with the same floating-point operations.

- A drone *measures* its SoC rounded to 0.1 % (:func:`measure`): features, bids, the take-off
  SoC and the abort check all use the measured value.
- Charging: ``100 - SoC`` shrinks by :attr:`Params.charge_keep` per tick; after n ticks at the
  centre ``SoC = 100 - (100 - SoC_landing) * KEEP[n]`` with ``KEEP`` a table built once by
  repeated multiplication (no ``pow``, whose vectorised and scalar versions may differ).
- Flight: a drone spends a fixed drain per tick (payload included until delivery, and after an
  abort, since it brings the parcel back); ``SoC = SoC_takeoff - n * drain`` after n ticks.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable

import numpy as np

from .params import Params

NEVER = np.iinfo(np.int64).max // 4     # "no such tick"; sums of two stay representable


def measure_level(soc):
    """The reading in 0.1 % steps: round(10 SoC), half up."""
    return np.floor(np.asarray(soc, dtype=float) * 10.0 + 0.5)


def measure(soc):
    """SoC as the drone reads it: rounded to 0.1 % (half up)."""
    return measure_level(soc) / 10.0


@lru_cache(maxsize=8)
def keep_table(keep: float) -> np.ndarray:
    """KEEP[n] = keep^n by repeated multiplication while 100 * KEEP[n] > 1e-6; the last entry,
    used for every later tick, is 0 (the battery is full)."""
    length = int(math.log(1e-8) / math.log(keep)) + 2
    table = np.zeros(length + 1)
    table[0] = 1.0
    np.multiply.accumulate(np.full(length - 1, keep), out=table[1:length])
    table.setflags(write=False)
    return table


@lru_cache(maxsize=8)
def keep_table_negated(keep: float) -> np.ndarray:
    """-KEEP, increasing, for ``searchsorted``."""
    table = -keep_table(keep)
    table.setflags(write=False)
    return table


def charged(params: Params, soc_landing, ticks):
    """SoC after ``ticks`` ticks of charging from ``soc_landing`` (arrays broadcast)."""
    table = keep_table(params.charge_keep)
    index = np.minimum(np.asarray(ticks, dtype=np.int64), len(table) - 1)
    return 100.0 - (100.0 - np.asarray(soc_landing, dtype=float)) * table[index]


def first_true(predicate: Callable[[np.ndarray], np.ndarray], lo, hi) -> np.ndarray:
    """Per element, the first integer n in [lo, hi] where the monotone (False...True)
    ``predicate(n)`` holds, else hi + 1. Vectorised bisection."""
    lo = np.array(lo, dtype=np.int64, copy=True)
    hi = np.array(hi, dtype=np.int64, copy=True) + 1
    lo, hi = np.broadcast_arrays(lo, hi)
    lo, hi = lo.copy(), hi.copy()
    while True:
        open_ = lo < hi
        if not open_.any():
            return lo
        mid = (lo + hi) // 2
        ok = predicate(mid) & open_
        hi = np.where(ok, mid, hi)
        lo = np.where(open_ & ~ok, mid + 1, lo)


def outbound_ticks(params: Params, distance):
    """Moves until the drone is within the delivery radius of the destination."""
    return np.floor((np.asarray(distance) - params.deliver_radius_m) / params.speed_ms).astype(np.int64) + 1


def return_ticks(params: Params, position):
    """Moves back until the drone is within the home radius of the centre (at least one)."""
    moves = np.floor((np.asarray(position, dtype=float) - params.home_radius_m) / params.speed_ms).astype(np.int64) + 1
    return np.maximum(moves, 1)


def lost_before_move(soc_takeoff, drain, j):
    """Outbound, before move j (tick T + j): the drone has spent j ticks (take-off tick
    included) and is lost if nothing is left."""
    return soc_takeoff - j * drain <= 0.0


def aborts_before_move(soc_takeoff, drain, limit, j):
    """The abort check before move j: the measured SoC after the previous tick <= limit."""
    return measure(soc_takeoff - j * drain) <= limit


def outbound_end(soc_takeoff, drain, limit, moves):
    """First j in 1..moves where the drone is lost or aborts (moves + 1: it delivers)."""
    soc_takeoff, drain, limit = (np.asarray(v, dtype=float) for v in (soc_takeoff, drain, limit))
    return first_true(lambda j: lost_before_move(soc_takeoff, drain, j)
                      | aborts_before_move(soc_takeoff, drain, limit, j), 1, moves)


def delivers(params: Params, distance, mass, soc, soh):
    """Ground truth: would a drone of health ``soh`` leaving with SoC ``soc`` deliver (d, m)
    without aborting or being lost? (arrays broadcast)"""
    distance, mass, soc, soh = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (distance, mass, soc, soh)))
    drain = params.drain_per_tick(mass, soh)
    limit = params.xi * measure(soc)
    moves = outbound_ticks(params, distance)
    return outbound_end(soc, drain, limit, moves) > moves
