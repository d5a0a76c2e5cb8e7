"""Upper bounds of the energy-replenishment study (the seed's section "Towards energy-efficient
long-term operations of robot swarms"): work and energy efficiency with fixed chargers
(equations 1-3) and with one mobile charger serving one worker (its transfer-period analysis).

Rates are per second and energies in the study's units; work is counted as the simulation counts
it, ``work_per_second`` units per second of working (ten 0.1-s steps of one unit each), so that
W is comparable with the simulated runs (design/STUDIES.md's worked check: W = 26,865 units).
The models assume no interference and optimal paths, so they bound what a simulation reaches."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

# The most transfer periods best_transfer_period tries (one every 0.1 s up to what a charger can
# give): a larger charger capacity is refused rather than searched for minutes or for ever.
MAX_TRANSFER_PERIODS = 100_000


class Infeasible(ValueError):
    """No cycle of the strategy exists at these rates: the bound is undefined (a trial still runs)."""


@dataclass(frozen=True)
class Rates:
    """One robot's energy model (per second) and the scenario around it."""

    capacity: float = 100.0        # c_max
    charge: float = 10.0           # nu_charge, gross, in the charging strip
    move: float = 1.0              # nu_move
    work: float = 1.0              # nu_work
    core: float = 0.05             # nu_min, always
    commute_m: float = 1.0         # between the strips' inner edges (x = -0.5 to +0.5)
    speed_ms: float = 0.12         # e-puck speed
    workers: int = 6               # n_w
    duration_s: float = 600.0      # tau
    work_per_second: float = 10.0  # units of work counted per second of working

    @property
    def commute_s(self) -> float:
        """Delta_commute: time to cross the commuter region."""
        return self.commute_m / self.speed_ms


@dataclass(frozen=True)
class Bound:
    """The bound's terms (seconds), duty cycle D_w, work W (units) and efficiency E."""

    work_s: float
    charge_s: float
    commute_s: float
    cycle_s: float
    duty_cycle: float
    work: float
    efficiency: float


def fixed_bound(r: Rates) -> Bound:
    """Equations 1-3: a worker leaves the base full, works until it has just the energy to come
    back, recharges to full, and repeats."""
    commute = r.commute_s
    if r.charge <= r.core:
        raise Infeasible("the charging rate %g does not exceed the core rate %g: a robot in the charging strip never "
                         "gains energy" % (r.charge, r.core))
    work_s = (r.capacity - 2 * (r.core + r.move) * commute) / (r.core + r.work)
    if work_s <= 0:
        raise Infeasible("a worker cannot reach the work region and come back on one charge "
                         "(capacity %g, commute %.2f s)" % (r.capacity, commute))
    charge_s = r.capacity / (r.charge - r.core)
    cycle_s = work_s + 2 * commute + charge_s
    duty = work_s / cycle_s
    efficiency = 1 - cycle_s * r.core / r.capacity - 2 * commute * r.move / r.capacity
    return Bound(work_s, charge_s, commute, cycle_s, duty, r.workers * duty * r.duration_s * r.work_per_second,
                 efficiency)


def constant_supply_bound(r: Rates) -> Bound:
    """The fixed-charger bound with the energy supply at the work region (no commute): the
    reference the seed measures mobile chargers against."""
    return fixed_bound(replace(r, commute_m=0.0))


@dataclass(frozen=True)
class MobileRates:
    """A mobile charger's energy model (per second) and the transfer."""

    capacity: float = 200.0        # c_m,max
    charge: float = 10.0           # nu_m,charge
    move: float = 1.0              # nu_m,move
    core: float = 0.05             # nu_m,min
    transfer: float = 10.0         # nu_transfer, what the charger gives per second
    loss: float = 0.0              # 1 - xi: the share of a transfer that is lost


@dataclass(frozen=True)
class MobileBound:
    """One transfer period's analysis: whether a charger can sustain it, whether the worker
    must rest, and the resulting duty cycle, work and efficiency."""

    transfer_s: float
    feasible: bool
    worker_rests: bool
    cycle_s: float
    work_s: float
    duty_cycle: float
    work: float
    efficiency: float


def mobile_bound(w: Rates, m: MobileRates, transfer_s: float) -> MobileBound:
    """The seed's single-charger, single-worker analysis for a transfer period ``transfer_s``.

    The worker receives ``min(transfer_s (xi nu_transfer - nu_w,min), c_w,max)``; the charger needs
    ``transfer_s (nu_m,min + nu_transfer) + 2 Delta_commute (nu_m,min + nu_m,move)`` (at most
    c_m,max) and recharges it at its net rate nu_m,charge - nu_m,min (the seed's text writes the
    sum of the two rates here; the net rate is what its fixed-charger analysis and its energy
    model use). If the charger's cycle is shorter than the worker's working cycle the worker
    never rests; if it is at least the worker's longest (all-resting) cycle no schedule exists;
    between the two the worker rests part of each cycle. W counts ``w.workers`` such pairs."""
    xi = 1 - m.loss
    received = min(transfer_s * (xi * m.transfer - w.core), w.capacity)
    desired = transfer_s * (m.core + m.transfer) + 2 * w.commute_s * (m.core + m.move)
    if received <= 0 or desired > m.capacity or m.charge <= m.core:    # the last: the charger never refills
        return MobileBound(transfer_s, False, False, 0.0, 0.0, 0.0, 0.0, 0.0)
    work_s = received / (w.core + w.work)
    worker_cycle_min = work_s + transfer_s
    worker_cycle_max = received / w.core + transfer_s if w.core > 0 else math.inf   # no core rate: rests for ever
    charger_cycle = desired / (m.charge - m.core) + transfer_s + 2 * w.commute_s
    if charger_cycle >= worker_cycle_max:
        return MobileBound(transfer_s, False, True, charger_cycle, 0.0, 0.0, 0.0, 0.0)
    rests = charger_cycle > worker_cycle_min
    cycle = charger_cycle if rests else worker_cycle_min
    if rests:   # work x and rest y fill the cycle outside the transfer with the energy received
        work_s = (received - w.core * (cycle - transfer_s)) / w.work
    duty = work_s / cycle
    spent = (cycle * (w.core + m.core) + 2 * w.commute_s * m.move + (1 - xi) * transfer_s * m.transfer
             + work_s * w.work)
    return MobileBound(transfer_s, True, rests, cycle, work_s, duty,
                       w.workers * duty * w.duration_s * w.work_per_second, work_s * w.work / spent)


def best_transfer_period(w: Rates, m: MobileRates, step_s: float = 0.1) -> MobileBound | None:
    """The feasible transfer period with the highest duty cycle and, among those, the longest
    (the seed expects the longest restless period to spend the least energy commuting per unit
    of work; restless periods share one duty cycle until the worker's capacity caps what a
    transfer can give). None when no period is feasible. Periods are tried every ``step_s`` s."""
    periods = (round(k * step_s, 9) for k in range(1, transfer_periods(m, step_s) + 1))
    candidates = [b for b in (mobile_bound(w, m, t) for t in periods) if b.feasible]
    if not candidates:
        return None
    best = max(b.duty_cycle for b in candidates)
    return [b for b in candidates if b.duty_cycle >= best - 1e-9][-1]


def transfer_periods(m: MobileRates, step_s: float = 0.1) -> int:
    """How many periods best_transfer_period tries: every ``step_s`` up to the longest a charger
    can give for; a ValueError past MAX_TRANSFER_PERIODS."""
    longest = m.capacity / (m.core + m.transfer)      # a charger cannot give for longer
    if not longest / step_s <= MAX_TRANSFER_PERIODS:
        raise ValueError("a charger of capacity %g giving %g a second (and %g to its core) could give for %g s: "
                         "the search of transfer periods stops at %g s" % (
                             m.capacity, m.transfer, m.core, longest, MAX_TRANSFER_PERIODS * step_s))
    return int(longest / step_s)


def strategy_bound(strategy: str, w: Rates, m: MobileRates) -> Bound | MobileBound | None:
    """The one bound of each strategy: what ``swarmvm bounds energy --strategy STRATEGY`` prints
    and what ``sim energy``, ``sweep energy`` and the summary table measure a trial against.
    Fixed chargers: equations 1-3. Mobile chargers: the seed's one-charger-per-worker analysis at
    its best transfer period (None when no period is feasible); its duty cycle equals the
    constant-supply bound's wherever a charger keeps up, and its efficiency counts the charger's
    energy, which the constant supply's (0.947 at the default rates: workers only) does not."""
    return fixed_bound(w) if strategy == "fixed" else best_transfer_period(w, m)
