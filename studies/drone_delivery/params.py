"""Parameters of one trial: Table 2 of the seed plus what the published runs did where the text
is silent (design/STUDIES.md), and the constants derived from them."""

from __future__ import annotations

import dataclasses
import math

from ..fields import non_finite

RULES = ("least-confident", "most-confident", "random", "threshold")
TICKS_PER_WEEK = 7 * 24 * 3600          # one tick is one simulated second
# What a trial holds in memory grows with these (each drone's VM, policy and state; the accuracy
# samples of each drone, drawn once per trial and kept; the orders of a run, all drawn at its
# start): past them it is refused before it starts rather than filling the machine. What each
# costs is in docs/limits.md.
MAX_DRONES = 10_000
MAX_ACCURACY_CELLS = 10_000_000         # drones x accuracy samples
MAX_ORDERS = 10_000_000                 # expected orders of the measured run, or of the pretraining
# The charging model keeps a table of 100 - SoC over the ticks of a full charge (energy.keep_table)
# and a flight counts its moves in integer ticks: both are bounded by what is physically a long
# time, so that extreme options are one line here instead of an overflow in the trial.
MAX_FULL_CHARGE_S = TICKS_PER_WEEK      # C / (P_c gamma_c)
MAX_FLIGHT_S = TICKS_PER_WEEK           # d-max-m, deliver-radius-m, home-radius-m flown at speed-ms
MAX_INIT_EPOCHS = 10_000                # each an SGD pass in pure Python, for every drone
MAX_DISTANCE_M = 2.0e7                  # half the Earth's circumference: no delivery is farther


def _refuse_first(checks) -> None:
    """A ValueError for the first (options, ok, message) not ok: "--option: message", or, where
    several options make the number together, "--a, --b: message"."""
    for options, ok, message in checks:
        if not ok:
            names = (options,) if isinstance(options, str) else options
            raise ValueError("%s: %s" % (", ".join("--" + name for name in names), message))


@dataclasses.dataclass(frozen=True)
class Params:
    """Everything a trial depends on; the defaults are Table 2 and the reference configuration."""

    rule: str = "least-confident"
    threshold: float = 0.8              # threshold rule: bid iff SoC >= threshold (fraction)
    forecast: bool = False              # reservation bids (the forecasting variant)
    pretrain_weeks: int = 0             # weeks of learning (no forecast) before the measured run
    tau_min: float = 20.0               # mean order inter-arrival time, minutes
    weeks: int = 8
    week_s: int = TICKS_PER_WEEK        # length of a "week" (reporting period); shorter for quick checks
    drones: int = 25
    seed: int = 1445
    frame_kg: float = 10.0
    battery_kg: float = 10.0
    rotors: int = 8
    disc_m2: float = 0.27
    speed_ms: float = 10.0
    capacity_wh: float = 800.0
    soh_min: float = 0.5
    soh_max: float = 1.0
    charger_w: float = 100.0
    charger_eff: float = 0.95
    d_min_m: float = 1000.0
    d_max_m: float = 6000.0
    m_min_kg: float = 0.5
    m_max_kg: float = 5.0
    gravity: float = 9.81
    air_density: float = 1.225
    xi: float = 0.5                     # abort when SoC <= xi * SoC_takeoff
    advert_period_s: int = 2
    deliver_radius_m: float = 80.0
    home_radius_m: float = 800.0
    alpha: float = 0.01
    init_epochs: int = 7                # epochs of the initial fit on the two assumed points
    accuracy_samples: int = 1000

    def __post_init__(self) -> None:
        if self.rule not in RULES:
            raise ValueError("--rule: must be one of %s, got %r" % (", ".join(RULES), self.rule))
        unusable = non_finite(self)
        if unusable:
            raise ValueError("--%s: must be a finite number, got %r" % (unusable.replace("_", "-"),
                                                                      getattr(self, unusable)))
        # The physics (equations 14 and 15) divides by rotors, disc area, capacity and speed.
        positive = ("frame_kg", "battery_kg", "disc_m2", "speed_ms", "capacity_wh", "charger_w", "gravity",
                    "air_density", "deliver_radius_m", "tau_min")
        checks = [(name.replace("_", "-"), getattr(self, name) > 0, "must be positive") for name in positive]
        checks += [("drones", self.drones >= 1, "must be at least 1"),
                  ("rotors", self.rotors >= 1, "must be at least 1"),
                  ("charger-eff", 0 < self.charger_eff <= 1, "must lie in (0, 1]"),
                  ("home-radius-m", self.home_radius_m >= 0, "must not be negative"),
                  # at 1 or more the first update's L2 shrink, 1 - alpha^0.75, zeroes the policy
                  ("alpha", 0 < self.alpha < 1, "must lie in (0, 1)"),
                  ("init-epochs", 0 <= self.init_epochs <= MAX_INIT_EPOCHS,
                   "must lie in [0, {:,}]".format(MAX_INIT_EPOCHS)),
                  ("weeks", self.weeks >= 0 and self.pretrain_weeks >= 0, "must not be negative"),
                  ("week-s", self.week_s >= 1, "must be positive"),
                  ("soh-min", 0 < self.soh_min <= self.soh_max <= 1, "need 0 < soh-min <= soh-max <= 1"),
                  ("d-min-m", 0 < self.d_min_m <= self.d_max_m, "need 0 < d-min-m <= d-max-m"),
                  *((name, getattr(self, name.replace("-", "_")) <= MAX_DISTANCE_M,
                     "must be at most {:,.0f} m (half the Earth's circumference)".format(MAX_DISTANCE_M))
                    for name in ("d-max-m", "deliver-radius-m", "home-radius-m")),
                  ("m-min-kg", 0 <= self.m_min_kg <= self.m_max_kg, "need 0 <= m-min-kg <= m-max-kg"),
                  ("xi", 0 < self.xi < 1, "must lie in (0, 1)"),
                  ("threshold", 0 <= self.threshold <= 1, "must lie in [0, 1]"),
                  ("advert-period-s", self.advert_period_s >= 2, "an auction takes 2 ticks: must be >= 2"),
                  ("accuracy-samples", self.accuracy_samples >= 1, "must be at least 1")]
        _refuse_first(checks)
        self._check_size()
        self._check_model()

    def _check_size(self) -> None:
        """The limits on what a trial keeps in memory (MAX_DRONES and the two below it)."""
        cells = self.drones * self.accuracy_samples
        orders = max(self.weeks, self.pretrain_weeks) * self.week_s / max(60.0 * self.tau_min, 1.0)
        _refuse_first((
                ("drones", self.drones <= MAX_DRONES, "must be at most {:,}".format(MAX_DRONES)),
                ("accuracy-samples", cells <= MAX_ACCURACY_CELLS,
                 "{:,} drones x {:,} samples pass {:,}, the most a trial keeps".format(
                     self.drones, self.accuracy_samples, MAX_ACCURACY_CELLS)),
                ("pretrain-weeks" if self.pretrain_weeks > self.weeks else "weeks", orders <= MAX_ORDERS,
                 "about {:,.0f} orders a run (weeks x week-s / tau-min) pass {:,}, the most a trial draws".format(
                     orders, MAX_ORDERS))))

    def _check_model(self) -> None:
        """The derived constants the trial computes with, at the extremes it reaches, as numbers
        it can take: each option is in range alone, but together they may not be."""
        try:
            drain = self.drain_per_tick(self.m_max_kg, self.soh_min)
        except (OverflowError, ZeroDivisionError):     # a power or a capacity beyond floating point
            drain = math.inf
        charge = self.charger_eff * self.charger_w / (3600.0 * self.capacity_wh)
        flight = max(self.d_max_m, self.deliver_radius_m, self.home_radius_m) / self.speed_ms
        _refuse_first((
                (("frame-kg", "battery-kg", "m-max-kg", "gravity", "rotors", "air-density", "disc-m2", "capacity-wh",
                  "soh-min"), math.isfinite(drain),
                 "give the heaviest flight a drain (equations 14 and 15) that is not a finite number"),
                (("capacity-wh", "charger-w", "charger-eff"), 0.0 < charge < 1.0 and self.full_charge_s <= MAX_FULL_CHARGE_S,
                 "a full charge, 3600 capacity-wh / (charger-w charger-eff), must take more than 1 s and at most "
                 "{:,} s".format(MAX_FULL_CHARGE_S)),
                (("d-max-m", "deliver-radius-m", "home-radius-m", "speed-ms"), flight <= MAX_FLIGHT_S,
                 "each distance must be flown within {:,} s".format(MAX_FLIGHT_S))))

    # -- derived constants ------------------------------------------------------------------------
    @property
    def horizon(self) -> int:
        """Ticks of the measured run."""
        return self.weeks * self.week_s

    def power_w(self, payload_kg):
        """Equation 14 in W: (g (m_f + m_b + m_p))^1.5 / sqrt(2 n_r rho zeta)."""
        mass = self.frame_kg + self.battery_kg + payload_kg
        return (self.gravity * mass) ** 1.5 / math.sqrt(2.0 * self.rotors * self.air_density * self.disc_m2)

    def drain_per_tick(self, payload_kg, soh):
        """Equation 15: SoC percentage points spent per second of flight."""
        return 100.0 * self.power_w(payload_kg) / (3600.0 * self.capacity_wh * soh)

    @property
    def charge_keep(self) -> float:
        """Equation 13 per second: 100 - SoC is multiplied by this factor every tick."""
        return 1.0 - self.charger_eff * self.charger_w / (3600.0 * self.capacity_wh)

    @property
    def full_charge_s(self) -> float:
        """C_theoretical / (P_c gamma_c) in s: the forecast's linear estimate of a full charge."""
        return 3600.0 * self.capacity_wh / (self.charger_w * self.charger_eff)

    @property
    def threshold_pct(self) -> float:
        return round(100.0 * self.threshold, 9)

    def replace(self, **changes) -> "Params":
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)
