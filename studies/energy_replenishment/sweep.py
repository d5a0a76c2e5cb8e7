"""The seed's grids of the energy-replenishment study (Figures 9-12), run by the studies' shared
sweep runner (studies/sweeps.py: local processes or a Dask cluster, resumable, one tidy Parquet
table ``trials``: a trial's parameters, results and bound in one row).

Figure 9: fixed chargers, and mobile chargers n_m x capacity ratio phi (6 workers). Figures
10-12: both strategies (mobile: 6 chargers of twice the workers' capacity) against the workload
ratio nu_work / nu_move, the charging (= transfer) rate and the transfer loss. The seed's text
does not list the axes of Figures 10-12; ours are below. A trial shared by several figures (the
default configuration) runs once: trials are keyed by their parameters."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Dict, Iterable, List, Optional, Sequence

from .. import sweeps
from . import plugin, trial
from .params import Params

if TYPE_CHECKING:
    import pandas

TABLES = ("trials",)
FIGURES = ("9", "10", "11", "12")
CHARGERS = (1, 2, 4, 6, 8, 10, 12)                 # Figure 9: n_m
CAPACITY_RATIOS = (1.0, 1.5, 2.0, 4.0, 6.0)        # Figure 9: phi = c_m,max / c_w,max
WORKLOAD_RATIOS = (0.25, 0.5, 1.0, 2.0, 4.0)       # Figure 10: nu_work / nu_move
CHARGE_RATES = (1.0, 2.5, 5.0, 7.5, 10.0)          # Figure 11: per second (0.1 .. 1 per step)
TRANSFER_LOSSES = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8)   # Figure 12: 1 - xi


def figure_cases(figure: str, base: Params) -> List[Params]:
    """One figure's configurations (seed not set)."""
    fixed = base.replace(strategy="fixed", chargers=0)
    mobile = base.replace(strategy="mobile", chargers=6, charger_capacity=2 * base.capacity)
    if figure == "9":
        return [fixed] + [base.replace(strategy="mobile", chargers=n, charger_capacity=phi * base.capacity)
                          for n in CHARGERS for phi in CAPACITY_RATIOS]
    if figure == "10":
        return [p.replace(work_rate=r * base.move_rate) for r in WORKLOAD_RATIOS for p in (fixed, mobile)]
    if figure == "11":
        return [p.replace(charge_rate=c, transfer_rate=c) for c in CHARGE_RATES for p in (fixed, mobile)]
    if figure == "12":   # the fixed strategy has no transfers: one reference configuration
        return [fixed] + [mobile.replace(transfer_loss=x) for x in TRANSFER_LOSSES]
    raise ValueError("unknown figure %r (one of %s)" % (figure, ", ".join(FIGURES)))


# What a figure's configurations derive from the options given, for the message when one of
# them is out of range although the options are not.
DERIVED = {"9": "gives the chargers up to %g times --capacity" % max(CAPACITY_RATIOS),
           "10": "sets the work rate up to %g times --move-rate" % max(WORKLOAD_RATIOS)}


def grid(base: Params, figures: Sequence[str] = FIGURES, seeds: Iterable[int] = range(1, 51)) -> List[Params]:
    """Every configuration of the figures x seeds, each once. A configuration out of range is a
    ValueError naming ``--figures``, the figure and what it derives from the options."""
    seeds = list(seeds)
    cases = {}
    for figure in figures:
        try:
            configurations = figure_cases(figure, base)
        except ValueError as exc:
            raise ValueError("--figures: Figure %s %s: %s" % (figure, DERIVED.get(figure, "sets its own rates"), exc)) \
                from None
        cases.update((tuple(sorted(c.to_dict().items())), c) for c in configurations)
    return [c.replace(seed=s) for c in cases.values() for s in seeds]


def trial_key(p: Params) -> str:
    """A readable, unique file name for a trial."""
    what = "fixed" if p.strategy == "fixed" else "mobile%d-cap%g" % (p.chargers, p.charger_capacity)
    return "%s-seed%d-%s" % (what, p.seed, sweeps.digest(p.to_dict()))


@lru_cache(maxsize=1)
def _library() -> Path:
    """The plugin, built (or found in the cache) once per process."""
    return plugin.build()


def run_trial(p: Params) -> Dict[str, list]:
    """One trial in ARGoS: its row (parameters, results, bound)."""
    result = trial.run(p, _library())
    row = dict(key=trial_key(p), **p.to_dict())
    row.update(result)
    return dict(trials=[row])


def sweep(specs: Sequence[Params], out, workers: int = 1, scheduler: Optional[str] = None,
          progress: bool = True) -> int:
    """Runs the trials of ``specs`` not yet in ``out``; returns how many ran. The plugin is built
    here first, so that the trials only find it in the cache (workers share the file system)."""
    _library()
    return sweeps.run(specs, trial_key, run_trial, out, TABLES, workers=workers, scheduler=scheduler,
                      progress=progress)


def load(out) -> "pandas.DataFrame":
    """The trials table, in key order."""
    return sweeps.load(out, TABLES)["trials"]
