"""The studies' subcommands of ``swarmvm sim|sweep|plot|bounds <study>``: the drone-delivery
study's (``uav``) here, the energy-replenishment study's (``energy``) in energy_commands.

The verbs themselves are groups of the main command line (swarmvm.cli.commands), which imports
:data:`SUBCOMMANDS` only when one of them runs or shows its help: the compiler's verbs never
import the studies."""

from __future__ import annotations

import dataclasses
import json

import click

from ..boundary import terminal
from ..boundary.errors import InputError
from ..cli.options import SEED, SEED_MAX, FiniteFloat
from . import energy_commands, sweeps
from .drone_delivery.params import RULES, Params
from .extra import need_studies_extra
from .sweep_options import PROCESSES, RUNS, sweep_seeds

# Help for the options generated from Params (one per field; defaults are Table 2's).
HELP = dict(
    rule="Winner rule (learning) or the threshold baseline.", threshold="Threshold rule: bid iff SoC >= this fraction.",
    forecast="Forecasting variant: reservation bids.", pretrain_weeks="Weeks of learning before the measured run.",
    tau_min="Mean order inter-arrival time (minutes).", weeks="Operation period (weeks).",
    week_s="Seconds per week (the reporting period); shorter only for quick checks.", drones="Swarm size S.",
    seed="Seed of the trial.", frame_kg="Frame mass m_f (kg).", battery_kg="Battery mass m_b (kg).",
    rotors="Number of rotors n_r.", disc_m2="Area of one rotor disc zeta (m^2).", speed_ms="Speed v_a (m/s).",
    capacity_wh="Theoretical battery capacity (Wh).", soh_min="Lowest battery health.", soh_max="Highest battery health.",
    charger_w="Charger power P_c (W).", charger_eff="Charger efficiency gamma_c.", d_min_m="Shortest delivery (m).",
    d_max_m="Longest delivery (m).", m_min_kg="Lightest parcel (kg).", m_max_kg="Heaviest parcel (kg).",
    gravity="g (m/s^2).", air_density="Air density rho (kg/m^3).", xi="Abort at SoC <= xi * SoC_takeoff.",
    advert_period_s="Seconds between advertisements.", deliver_radius_m="Delivered within this distance (m).",
    home_radius_m="Home within this distance of the centre (m).", alpha="Regularisation strength of the learning.",
    init_epochs="Epochs of the initial fit on the two assumed points.",
    accuracy_samples="Random feature vectors per drone for the weekly accuracy.")


def option_type(field: dataclasses.Field):
    """The click type of a Params field's option: floats must be finite, the seed is a seed;
    Params checks the other ranges itself (its messages name the option)."""
    if field.name == "seed":
        return SEED
    return FiniteFloat() if isinstance(field.default, float) else type(field.default)


def params_options(exclude=()):
    """Decorator: one click option per Params field (``--tau-min`` for ``tau_min``)."""
    def decorate(command):
        for field in reversed(dataclasses.fields(Params)):
            if field.name in exclude:
                continue
            flag = "--" + field.name.replace("_", "-")
            if field.name == "rule":
                command = click.option(flag, type=click.Choice(RULES), default=field.default, show_default=True,
                                       help=HELP[field.name])(command)
            elif isinstance(field.default, bool):
                command = click.option(flag, is_flag=True, help=HELP[field.name])(command)
            else:
                command = click.option(flag, type=option_type(field), default=field.default, show_default=True,
                                       help=HELP[field.name])(command)
        return command
    return decorate


class FloatList(click.ParamType):
    """Comma-separated numbers of ``item``'s range ('' for none): a sweep's grid along one parameter."""

    name = "numbers"

    def __init__(self, item: FiniteFloat) -> None:
        self.item = item

    def convert(self, value, param, ctx):
        if not isinstance(value, str):
            return value
        return [self.item.convert(text.strip(), param, ctx) for text in value.split(",") if text.strip()]


def make_params(values: dict) -> Params:
    """Params from option values; a bad combination is the CLI's one-line error, exit 2."""
    try:
        return Params(**values)
    except ValueError as exc:
        terminal.fail(exc)


@click.command("uav")
@params_options()
@click.option("--mode", type=click.Choice(["event", "tick"]), default="event", show_default=True,
              help="Event-driven engine, or plain tick by tick (slow; for validation).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def sim_uav(mode, as_json, **values):
    """Drone delivery (the seed's online-learning study): one trial."""
    need_studies_extra()
    from .drone_delivery.engine import run
    result = run(make_params(values), mode=mode)
    summary = result.summary()
    if as_json:
        terminal.line(json.dumps(summary, sort_keys=True))
        return
    for name in ("orders", "delivered", "pending", "aborted", "takeoffs", "advertisements", "lost", "reservations",
                 "median_delivery_min", "mean_delivery_min"):
        terminal.line("%-20s %s" % (name, summary[name]))
    terminal.line("%-20s %s" % ("accuracy_by_week", " ".join("%.3f" % a for a in summary["accuracy_by_week"])))
    terminal.line("%-20s %.2f s (CPU %.2f s)" % ("time", summary["seconds"], summary["cpu_seconds"]))


@click.command("uav")
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Results folder (Parquet).")
@click.option("--rules", default="least-confident,most-confident,random", show_default=True,
              help="Learning rules (comma-separated); '' for none.")
@click.option("--thresholds", default="0.5,0.6,0.7,0.8,0.9,1.0", show_default=True, type=FloatList(FiniteFloat(0, 1)),
              help="Threshold-rule runs at these thresholds; '' for none.")
@click.option("--taus", default="5,10,15,20,25,30", show_default=True, type=FloatList(FiniteFloat(min=0, min_open=True)),
              help="Inter-arrival means (minutes).")
@click.option("--runs", default=20, show_default=True, type=RUNS, help="Runs per configuration.")
@click.option("--first-seed", default=1, show_default=True, type=SEED, help="Runs use seeds first..first+runs-1.")
@click.option("--workers", default=1, show_default=True, type=PROCESSES, help="Local processes.")
@click.option("--scheduler", default=None, help="Dask scheduler address: run there instead of locally.")
@click.option("--no-progress", is_flag=True, help="No progress bar.")
@params_options(exclude=("rule", "threshold", "tau_min", "seed"))
def sweep_uav(out, rules, thresholds, taus, runs, first_seed, workers, scheduler, no_progress, **values):
    """Drone delivery: rules x thresholds x tau x runs; finished trials are not rerun."""
    need_studies_extra()
    from .drone_delivery import sweep as grid_sweep
    rule_list = [r for r in rules.split(",") if r.strip()]
    bad = [r for r in rule_list if r not in grid_sweep.LEARNING_RULES]
    if bad:
        terminal.fail("--rules: unknown rule %r (one of %s)" % (bad[0], ", ".join(grid_sweep.LEARNING_RULES)))
    # The other options are checked at the largest tau (the fewest orders), each tau by the grid.
    base = make_params(dict(values, tau_min=max(taus)) if taus else values)
    try:
        specs = grid_sweep.grid(base, rule_list, thresholds, taus, sweep_seeds(first_seed, runs, SEED_MAX))
    except ValueError as exc:           # a tau the other parameters cannot take
        terminal.fail(exc)
    try:
        ran = grid_sweep.sweep(specs, out, workers=workers, scheduler=scheduler, progress=not no_progress)
    except (sweeps.SchedulerError, InputError) as exc:     # InputError: a trial's table cannot be written there
        terminal.fail(exc)
    terminal.line("%d trials run, %d already done; results in %s" % (ran, len(specs) - ran, out))


@click.command("uav")
@click.argument("results", type=click.Path(exists=True, file_okay=False))
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Folder for the PNG files.")
@click.option("--tau", default=20.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="Inter-arrival mean of Figures 17, 18 and 20.")
def plot_uav(results, out, tau):
    """Drone delivery: the seed's Figures 16-20 (and a summary table) from sweep results."""
    need_studies_extra()
    from .drone_delivery import plots
    try:
        sweeps.check_trials(results, "tau_min", "swarmvm sweep uav")
    except (ValueError, InputError) as exc:
        terminal.fail(exc)
    try:
        paths, missing = plots.draw_all(results, out, tau=tau)
    except InputError as exc:           # a table that cannot be read, a figure that cannot be written
        terminal.fail(exc)
    for path in paths:
        terminal.line(path)
    for text in missing:
        terminal.note("uav: %s: give --tau one of them" % text)


# Each verb's subcommands, one per study (the verb's group is swarmvm.cli.commands's).
SUBCOMMANDS: dict[str, tuple[click.Command, ...]] = {
    "sim": (sim_uav, energy_commands.sim_energy),
    "sweep": (sweep_uav, energy_commands.sweep_energy),
    "plot": (plot_uav, energy_commands.plot_energy),
    "bounds": (energy_commands.bounds_energy,),
}
__all__ = ["SUBCOMMANDS"]
