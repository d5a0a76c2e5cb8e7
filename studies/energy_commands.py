"""``swarmvm sim|sweep|plot energy``: the energy-replenishment study in real ARGoS, and
``swarmvm bounds energy``, its theoretical bounds. cli.py lists them among the studies'
subcommands (its SUBCOMMANDS); this module imports nothing of cli.py."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import click

from ..boundary import terminal
from ..boundary.errors import InputError
from ..cli.options import FiniteFloat
from . import sweeps
from .energy_replenishment.params import MAX_DURATION_S, MAX_ROBOTS, MAX_SEED, MIN_SEED, STRIP_HALF_WIDTH_M
from .extra import need_studies_extra
from .sweep_options import PROCESSES, RUNS, sweep_seeds

# The energy study's seeds (sim --seed, sweep --first-seed): what ARGoS repeats (params.MIN_SEED).
ARGOS_SEED = click.IntRange(MIN_SEED, MAX_SEED)

# The type of both energy verbs' --work-rate (sim|sweep|plot energy, bounds energy): working must
# spend energy. The efficiency is the share of energy spent working (0 whatever the robots do at
# a work rate of 0), and the mobile bound divides by the work rate.
WORK_RATE = FiniteFloat(min=0, min_open=True)

# Options shared by `sim energy` and `sweep energy`: (flag, Params field, type, help).
RATE_OPTIONS = (
    ("--capacity", "capacity", FiniteFloat(min=0, min_open=True), "Worker capacity c_w,max."),
    ("--charger-capacity", "charger_capacity", FiniteFloat(min=0, min_open=True), "Mobile charger capacity c_m,max."),
    ("--charge-rate", "charge_rate", FiniteFloat(min=0, min_open=True),
     "Charging rate per second in the charging strip (and the transfer rate unless --transfer-rate)."),
    ("--transfer-rate", "transfer_rate", FiniteFloat(min=0, min_open=True),
     "What a mobile charger gives per second."),
    ("--transfer-loss", "transfer_loss", FiniteFloat(0, 1, max_open=True), "Share of a transfer that is lost (1 - xi)."),
    ("--move-rate", "move_rate", FiniteFloat(min=0), "Moving, per second."),
    ("--work-rate", "work_rate", WORK_RATE, "Working, per second."),
    ("--core-rate", "core_rate", FiniteFloat(min=0), "Core, per second."),
    ("--duration", "duration_s", FiniteFloat(min=0, min_open=True, max=MAX_DURATION_S), "Trial length, seconds."),
    ("--strip-inset", "strip_inset_m", FiniteFloat(0, STRIP_HALF_WIDTH_M),
     "How far inside a strip's edges a robot stays, m (0.15: on the strip's centre line)."),
)


def rate_options(command):
    """One option per RATE_OPTIONS entry, Params' default its default (shown as every verb shows
    one); --transfer-rate not given (None) follows the charge rate."""
    from .energy_replenishment.params import Params
    for flag, field, kind, text in reversed(RATE_OPTIONS):
        if field == "transfer_rate":
            command = click.option(flag, type=kind, default=None, show_default="the charge rate", help=text)(command)
        else:
            command = click.option(flag, type=kind, default=getattr(Params(), field), show_default=True,
                                   help=text)(command)
    return command


def params_from(values: dict, **fixed):
    """Params from the options given (others keep Params' defaults); a bad combination is the
    CLI's one-line error, exit 2."""
    from .energy_replenishment.params import Params
    changes = {field: values.pop(flag.lstrip("-").replace("-", "_")) for flag, field, _kind, _text in RATE_OPTIONS}
    changes = {k: v for k, v in changes.items() if v is not None}
    if "charge_rate" in changes and "transfer_rate" not in changes:
        changes["transfer_rate"] = changes["charge_rate"]
    try:
        return Params(**changes, **fixed)
    except ValueError as exc:
        fail("%s" % exc)


def fail(message: str, status: int = 2):
    terminal.fail("energy: %s" % message, status)


@click.command("energy")
@click.option("--strategy", type=click.Choice(["fixed", "mobile"]), default="fixed", show_default=True,
              help="Workers recharge in the charging strip, or mobile chargers bring them energy.")
@click.option("--workers", default=6, show_default=True, type=click.IntRange(1, MAX_ROBOTS), help="n_w.")
@click.option("--chargers", default=4, show_default=True, type=click.IntRange(1, MAX_ROBOTS - 1),
              help="n_m (mobile strategy).")
@rate_options
@click.option("--seed", default=1, show_default=True, type=ARGOS_SEED,
              help="ARGoS random seed (0 would have ARGoS seed from the clock).")
@click.option("--trace", type=click.Path(dir_okay=False), default=None, help="Write every robot's step as CSV here.")
@click.option("--vm-traces", type=click.Path(file_okay=False), default=None,
              help="Write each robot's VM trace into this folder as SUPERVISOR/ROBOT.trace (swarmvm inspect reads them).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def sim_energy(strategy, workers, chargers, seed, trace, vm_traces, as_json, **values):
    """Energy replenishment: one 600-s trial in real ARGoS (the study plugin is built once)."""
    from .energy_replenishment import plugin, trial
    params = params_from(values, strategy=strategy, workers=workers, chargers=chargers if strategy == "mobile" else 0,
                         seed=seed)
    try:
        result = trial.run(params, trace=trace, vm_traces=vm_traces and Path(vm_traces).absolute())
    except (plugin.BuildError, trial.TrialError) as exc:
        fail(str(exc), 1)
    except InputError as exc:           # --vm-traces cannot be written there
        terminal.fail(exc)
    if as_json:
        terminal.line(json.dumps(result, sort_keys=True))
        return
    for key in ("work", "bound_work", "work_of_bound", "efficiency", "bound_efficiency", "depleted",
                "depleted_chargers", "consumed", "lost", "seconds"):
        value = result[key]
        terminal.line("%-18s %s" % (key, round(value, 4) if isinstance(value, float) else value))


@click.command("energy")
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Results folder (Parquet).")
@click.option("--figures", default="9,10,11,12", show_default=True, help="The seed's figures whose grids to run.")
@click.option("--runs", default=50, show_default=True, type=RUNS, help="Trials (seeds) per configuration.")
@click.option("--first-seed", default=1, show_default=True, type=ARGOS_SEED,
              help="Seeds first..first+runs-1.")
@click.option("--workers", default=1, show_default=True, type=PROCESSES, help="Local ARGoS processes at once.")
@click.option("--scheduler", default=None, help="Dask scheduler address: run there instead of locally.")
@click.option("--no-progress", is_flag=True, help="No progress bar.")
@rate_options
def sweep_energy(out, figures, runs, first_seed, workers, scheduler, no_progress, **values):
    """Energy replenishment: the grids of Figures 9-12 in real ARGoS; finished trials are not rerun."""
    need_studies_extra()
    from .energy_replenishment import plugin, trial
    from .energy_replenishment import sweep as grid_sweep
    wanted = [f.strip() for f in figures.split(",") if f.strip()]
    bad = [f for f in wanted if f not in grid_sweep.FIGURES]
    if bad or not wanted:
        fail("--figures: unknown figure %r (some of %s)" % (bad[0] if bad else figures, ", ".join(grid_sweep.FIGURES)))
    try:
        specs = grid_sweep.grid(params_from(values), wanted, sweep_seeds(first_seed, runs, MAX_SEED))
    except ValueError as exc:           # a configuration a figure derives out of range
        fail(str(exc))
    try:
        ran = grid_sweep.sweep(specs, out, workers=workers, scheduler=scheduler, progress=not no_progress)
    except (plugin.BuildError, trial.TrialError) as exc:
        fail(str(exc), 1)
    except (sweeps.SchedulerError, InputError) as exc:     # InputError: a trial's table cannot be written there
        fail(str(exc))
    terminal.line("%d trials run, %d already done; results in %s" % (ran, len(specs) - ran, out))


@click.command("energy")
@click.argument("results", type=click.Path(exists=True, file_okay=False))
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Folder for the PNG files.")
@rate_options
def plot_energy(results, out, **values):
    """Energy replenishment: the seed's Figures 9-12 (and a summary table) from sweep results, at
    the rates the sweep was given (the same options)."""
    need_studies_extra()
    from .energy_replenishment import plots
    base = params_from(values)
    try:
        sweeps.check_trials(results, "strategy", "swarmvm sweep energy")
    except (ValueError, InputError) as exc:
        fail(str(exc))
    try:
        paths, missing = plots.draw_all(results, out, base)
    except InputError as exc:           # a table that cannot be read, a figure that cannot be written
        fail(str(exc))
    for path in paths:
        terminal.line(path)
    for title in missing:
        terminal.note("energy: %s: no trials at these rates (give plot the rate options the sweep had, and a "
                      "sweep of its --figures)" % title)


@click.command("energy")
@click.option("--strategy", type=click.Choice(["fixed", "mobile"]), default="fixed", show_default=True,
              help="Fixed chargers (equations 1-3) or one mobile charger per worker.")
@click.option("--workers", default=6, show_default=True, type=click.IntRange(1), help="n_w.")
@click.option("--capacity", default=100.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="Worker capacity c_w,max.")
@click.option("--charge-rate", default=10.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="Charging rate per second (workers and chargers).")
@click.option("--move-rate", default=1.0, show_default=True, type=FiniteFloat(min=0), help="Moving, per second.")
@click.option("--work-rate", default=1.0, show_default=True, type=WORK_RATE, help="Working, per second.")
@click.option("--core-rate", default=0.05, show_default=True, type=FiniteFloat(min=0), help="Core, per second.")
@click.option("--commute-m", default=1.0, show_default=True, type=FiniteFloat(min=0),
              help="Distance between the charging (or transfer) and work regions.")
@click.option("--speed", default=0.12, show_default=True, type=FiniteFloat(min=0, min_open=True), help="m/s.")
@click.option("--duration", default=600.0, show_default=True, type=FiniteFloat(min=0), help="tau, seconds.")
@click.option("--charger-capacity", default=200.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="Mobile charger capacity c_m,max.")
@click.option("--transfer-rate", default=10.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="What a mobile charger gives per second.")
@click.option("--transfer-loss", default=0.0, show_default=True, type=FiniteFloat(0, 1, max_open=True),
              help="Share of a transfer that is lost (1 - xi).")
@click.option("--transfer-period", type=FiniteFloat(min=0, min_open=True), default=None,
              help="Mobile: analyse this transfer period (s) instead of finding the best.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def bounds_energy(strategy, workers, capacity, charge_rate, move_rate, work_rate, core_rate, commute_m, speed,
                  duration, charger_capacity, transfer_rate, transfer_loss, transfer_period, as_json):
    """Energy replenishment: work W, duty cycle and efficiency E the strategy cannot exceed."""
    from .energy_replenishment import bounds as energy
    rates = energy.Rates(capacity=capacity, charge=charge_rate, move=move_rate, work=work_rate, core=core_rate,
                         commute_m=commute_m, speed_ms=speed, workers=workers, duration_s=duration)
    try:
        mobile = energy.MobileRates(capacity=charger_capacity, charge=charge_rate, move=move_rate, core=core_rate,
                                    transfer=transfer_rate, loss=transfer_loss)
        found = (energy.mobile_bound(rates, mobile, transfer_period) if strategy == "mobile" and transfer_period
                 else energy.strategy_bound(strategy, rates, mobile))
        if found is None or not getattr(found, "feasible", True):
            raise ValueError("no feasible transfer period: a charger cannot sustain a worker with these rates")
        result = dict(dataclasses.asdict(found), constant_supply_work=energy.constant_supply_bound(rates).work)
    except ValueError as exc:
        terminal.fail("bounds energy: %s" % exc)
    if as_json:
        terminal.line(json.dumps(result, sort_keys=True))
        return
    for key, value in result.items():
        terminal.line("%-22s %s" % (key, round(value, 4) if isinstance(value, float) else value))
