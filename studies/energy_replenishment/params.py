"""One configuration of the energy-replenishment trial in ARGoS. Rates are per second, as in
:mod:`.bounds` and ``swarmvm bounds energy`` (design/STUDIES.md's: capacity 100, charging 10,
moving 1, working 1, core 0.05 per second); the simulation applies them per 0.1-s step."""

from __future__ import annotations

import dataclasses

from ..fields import non_finite
from . import bounds

STRATEGIES = ("fixed", "mobile")
TICKS_PER_SECOND = 10
# ARGoS keeps an experiment's length as a 32-bit count of clock ticks (its simulator.cpp casts
# length x ticks_per_second to UInt32): a longer one would wrap round, or never end.
MAX_DURATION_S = (2 ** 32 - 1) // TICKS_PER_SECOND
# The seeds a trial can give ARGoS as its random_seed: a 32-bit number, 0 excluded (ARGoS then
# seeds from the clock, and the trial would not repeat).
MIN_SEED, MAX_SEED = 1, 2 ** 32 - 1
# Robots a trial starts with (workers, and chargers with the mobile strategy), each at a random
# place in the charging strip: ARGoS gives up placing a few more than this (docs/limits.md).
MAX_ROBOTS = 40
# Energy capacities (workers' and chargers'): the loop functions sum energies over robots and
# steps, which must stay finite numbers in their JSON totals.
MAX_CAPACITY = 1e9
STRIP_HALF_WIDTH_M = 0.15           # the strips are 0.3 m wide (argos/energy_agent.h)


@dataclasses.dataclass(frozen=True)
class Params:
    """Every knob of a trial; the seed included, so a trial is a pure function of its Params."""

    strategy: str = "fixed"
    workers: int = 6
    chargers: int = 4                 # mobile strategy only
    capacity: float = 100.0           # worker c_w,max
    charger_capacity: float = 200.0   # c_m,max
    charge_rate: float = 10.0         # per second, in the charging strip
    transfer_rate: float = 10.0       # per second, what a charger gives
    transfer_loss: float = 0.0        # 1 - xi
    move_rate: float = 1.0
    work_rate: float = 1.0
    core_rate: float = 0.05
    speed_cms: float = 12.0           # e-puck top speed
    steering_noise: float = 0.05      # rad, standard deviation per step
    strip_inset_m: float = 0.02       # a robot in a strip stays this far from its edges (0.15: on its centre line)
    duration_s: float = 600.0
    seed: int = 1

    def __post_init__(self) -> None:
        checks = [(self.strategy in STRATEGIES, "strategy must be one of %s" % ", ".join(STRATEGIES)),
                  (non_finite(self) is None, "every rate and length must be a finite number"),
                  (self.workers >= 1, "workers must be at least 1"),
                  (self.chargers >= 0, "chargers must not be negative"),
                  (self.strategy == "fixed" or self.chargers >= 1, "the mobile strategy needs at least one charger"),
                  (self.workers + (self.chargers if self.strategy == "mobile" else 0) <= MAX_ROBOTS,
                   "at most %d robots start in the charging strip (workers, and chargers with the mobile strategy)"
                   % MAX_ROBOTS),
                  (self.capacity > 0 and self.charger_capacity > 0, "capacities must be positive"),
                  (self.capacity <= MAX_CAPACITY and self.charger_capacity <= MAX_CAPACITY,
                   "capacities must be at most %g" % MAX_CAPACITY),
                  (self.charge_rate > 0 and self.transfer_rate > 0, "charge and transfer rates must be positive"),
                  (0 <= self.transfer_loss < 1, "transfer loss must be in [0, 1)"),
                  (self.move_rate >= 0 and self.core_rate >= 0, "rates must not be negative"),
                  (self.work_rate > 0, "the work rate must be positive (working must spend energy)"),
                  (self.speed_cms > 0 and self.duration_s > 0, "speed and duration must be positive"),
                  # ARGoS truncates length x ticks_per_second to whole steps, and runs 0 steps for ever
                  (self.duration_s * TICKS_PER_SECOND >= 1,
                   "duration must be at least one control step, %g s (ARGoS runs an experiment of 0 steps for ever)"
                   % (1 / TICKS_PER_SECOND)),
                  (self.duration_s <= MAX_DURATION_S, "duration must be at most %d s (ARGoS counts an experiment's "
                                                      "length in 32-bit clock ticks)" % MAX_DURATION_S),
                  (self.steering_noise >= 0, "steering noise must not be negative"),
                  (0 <= self.strip_inset_m <= STRIP_HALF_WIDTH_M,
                   "the strip inset must be in [0, %g] m (half a strip's width)" % STRIP_HALF_WIDTH_M),
                  (MIN_SEED <= self.seed <= MAX_SEED, "seed must be in [%d, %d] (ARGoS seeds 0 from the clock)" % (MIN_SEED, MAX_SEED))]
        for ok, message in checks:
            if not ok:
                raise ValueError(message)
        if self.strategy == "mobile":
            bounds.transfer_periods(self.mobile_rates())    # the bound's search, before ARGoS runs

    def per_step(self, rate: float) -> float:
        return rate / TICKS_PER_SECOND

    def rates(self) -> bounds.Rates:
        """The same scenario for the bounds."""
        return bounds.Rates(capacity=self.capacity, charge=self.charge_rate, move=self.move_rate,
                            work=self.work_rate, core=self.core_rate, speed_ms=self.speed_cms / 100,
                            workers=self.workers, duration_s=self.duration_s,
                            work_per_second=TICKS_PER_SECOND)

    def mobile_rates(self) -> bounds.MobileRates:
        """The chargers' side of the same scenario (they charge at the strip's rate)."""
        return bounds.MobileRates(capacity=self.charger_capacity, charge=self.charge_rate, move=self.move_rate,
                                  core=self.core_rate, transfer=self.transfer_rate, loss=self.transfer_loss)

    def bound(self) -> bounds.Bound | bounds.MobileBound | None:
        """What the trial is measured against: its strategy's bound (:func:`bounds.strategy_bound`,
        the same numbers as ``swarmvm bounds energy``); None when there is none: fixed chargers
        whose workers cannot commute on one charge, mobile chargers that no transfer period can
        sustain."""
        try:
            return bounds.strategy_bound(self.strategy, self.rates(), self.mobile_rates())
        except bounds.Infeasible:
            return None

    def replace(self, **changes) -> "Params":
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)
