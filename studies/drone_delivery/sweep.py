"""Sweeps of trials: the seed's grid (rules and thresholds x tau x runs), run by the studies'
shared runner (studies/sweeps.py: local processes or a Dask cluster, resumable, tidy Parquet).

Every trial is a pure function of its :class:`Params` (its seed included). Tables: ``trials``
(one row per trial), ``accuracy`` (trial x week x drone), ``backlog`` (trial x arrival week),
``drones`` (trial x drone: health and final policy)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Dict, Iterable, List, Optional, Sequence

import numpy as np

from .. import sweeps
from .engine import run
from .params import Params

if TYPE_CHECKING:
    import pandas

TABLES = ("accuracy", "backlog", "drones", "trials")     # trials last: it marks a trial done
LEARNING_RULES = ("least-confident", "most-confident", "random")
SEED_TAUS = (5, 10, 15, 20, 25, 30)
SEED_THRESHOLDS = (0.5, 0.6, 0.7, 0.8, 0.9, 1.0)


def grid(base: Params, rules: Sequence[str] = LEARNING_RULES, thresholds: Sequence[float] = SEED_THRESHOLDS,
         taus: Sequence[float] = SEED_TAUS, seeds: Iterable[int] = range(1, 21)) -> List[Params]:
    """Learning rules x tau x seeds, plus the threshold rule at each threshold x tau x seeds. A tau
    the other parameters cannot take (too many orders at it) is a ValueError naming ``--taus``."""
    seeds = list(seeds)
    cases = [dict(rule=r) for r in rules] + [dict(rule="threshold", threshold=h) for h in thresholds]
    at_tau = []
    for tau in taus:
        try:
            at_tau.append(base.replace(tau_min=float(tau)))
        except ValueError as exc:
            raise ValueError("--taus: at %g minutes, %s" % (tau, exc)) from None
    return [p.replace(seed=seed, **case) for case in cases for p in at_tau for seed in seeds]


def trial_key(params: Params) -> str:
    """A readable, unique file name for a trial."""
    rule = params.rule if params.rule != "threshold" else "threshold%g" % params.threshold
    return "%s-tau%g-seed%d-%s" % (rule, params.tau_min, params.seed, sweeps.digest(params.to_dict()))


def run_trial(params: Params) -> Dict[str, list]:
    """Run one trial; its rows for every table (plain lists of dicts, cheap to ship back)."""
    result = run(params)
    key = trial_key(params)
    summary = result.summary()
    row = dict(key=key, **{k: v for k, v in params.to_dict().items()})
    for name in ("orders", "delivered", "pending", "aborted", "takeoffs", "advertisements", "lost",
                 "reservations", "median_delivery_min", "mean_delivery_min", "seconds", "cpu_seconds"):
        row[name] = summary[name]
    accuracy = [dict(key=key, week=w, drone=d, accuracy=float(a))
                for w, values in enumerate(result.accuracy) for d, a in enumerate(values)]
    backlog = [dict(key=key, arrival_week=w, pending=int(n), backlog_age_h=float(h))
               for w, (n, h) in enumerate(zip(summary["pending_by_week"], summary["backlog_age_h_by_week"]))]
    drones = [dict(key=key, drone=d, soh=float(result.soh[d]), w_distance=float(result.weights[d, 0]),
                   w_mass=float(result.weights[d, 1]), w_soc=float(result.weights[d, 2]),
                   intercept=float(result.intercept[d]), lost=bool(result.lost[d]))
              for d in range(len(result.soh))]
    return dict(trials=[row], accuracy=accuracy, backlog=backlog, drones=drones)


def sweep(specs: Sequence[Params], out, workers: int = 1, scheduler: Optional[str] = None,
          progress: bool = True) -> int:
    """Run the trials of ``specs`` not yet in ``out``; returns how many ran (studies/sweeps.py:
    ``workers`` local processes, or a Dask ``scheduler`` address or client)."""
    return sweeps.run(specs, trial_key, run_trial, out, TABLES, workers=workers, scheduler=scheduler,
                      progress=progress)


def load(out) -> Dict[str, "pandas.DataFrame"]:
    """Every table of a sweep, sorted (trial key, then the table's own index columns)."""
    return sweeps.load(out, TABLES, ("key", "week", "arrival_week", "drone"))


def summarise(frames) -> "pandas.DataFrame":
    """Medians per configuration (rule, threshold, tau): the numbers of the reproduction tables."""
    trials = frames["trials"].copy()
    trials["aborted_pct"] = 100.0 * trials["aborted"] / trials["takeoffs"].where(trials["takeoffs"] > 0)
    final = frames["accuracy"].groupby("key")["week"].transform("max") == frames["accuracy"]["week"]
    accuracy = frames["accuracy"][final].groupby("key")["accuracy"].mean().rename("final_accuracy")
    trials = trials.join(accuracy, on="key")
    trials["threshold"] = np.where(trials["rule"] == "threshold", trials["threshold"], np.nan)
    columns = ["delivered", "pending", "aborted", "aborted_pct", "median_delivery_min", "final_accuracy"]
    columns += [c for c in ("seconds", "cpu_seconds") if c in trials.columns]
    grouped = trials.groupby(["rule", "threshold", "tau_min", "forecast"], dropna=False)[columns]
    return grouped.median().join(grouped.size().rename("runs")).reset_index()
