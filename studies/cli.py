"""Command groups of the studies: ``swarmvm sim|sweep|plot <study>`` (registered by the main
command line). Each study adds one subcommand per group; the drone-delivery study is ``uav``."""

from __future__ import annotations

import dataclasses
import importlib.util
import json

import click

from .. import terminal
from ..options import SEED, FiniteFloat
from .drone_delivery.params import RULES, Params

# The type of both energy verbs' --work-rate (sim|sweep|plot energy, bounds energy): working must
# spend energy. The efficiency is the share of energy spent working (0 whatever the robots do at
# a work rate of 0), and the mobile bound divides by the work rate.
WORK_RATE = FiniteFloat(min=0, min_open=True)

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


# What `pip install "swarmvm[studies]"` adds (pyproject.toml), by import name.
STUDIES_EXTRA = ("numpy", "pandas", "pyarrow", "dask", "tqdm", "matplotlib")


def need_studies_extra() -> None:
    """Ends with one line and exit status 2 when the studies' dependencies are not installed
    (a plain `pip install swarmvm` leaves them out), instead of an ImportError traceback."""
    missing = [name for name in STUDIES_EXTRA if importlib.util.find_spec(name) is None]
    if missing:
        terminal.fail("the studies need %s: pip install \"swarmvm[studies]\"" % ", ".join(missing))


@click.group()
def sim():
    """Run one trial of a study."""


@click.group()
def sweep():
    """Run a study's grid of trials (resumable; local processes or a Dask cluster)."""


@click.group()
def plot():
    """Draw a study's figures from sweep results."""


@sim.command("uav")
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


@sweep.command("uav")
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Results folder (Parquet).")
@click.option("--rules", default="least-confident,most-confident,random", show_default=True,
              help="Learning rules (comma-separated); '' for none.")
@click.option("--thresholds", default="0.5,0.6,0.7,0.8,0.9,1.0", show_default=True, type=FloatList(FiniteFloat(0, 1)),
              help="Threshold-rule runs at these thresholds; '' for none.")
@click.option("--taus", default="5,10,15,20,25,30", show_default=True, type=FloatList(FiniteFloat(min=0, min_open=True)),
              help="Inter-arrival means (minutes).")
@click.option("--runs", default=20, show_default=True, type=click.IntRange(1), help="Runs per configuration.")
@click.option("--first-seed", default=1, show_default=True, type=SEED, help="Runs use seeds first..first+runs-1.")
@click.option("--workers", default=1, show_default=True, type=click.IntRange(1), help="Local processes.")
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
    specs = grid_sweep.grid(make_params(values), rule_list, thresholds, taus, range(first_seed, first_seed + runs))
    ran = grid_sweep.sweep(specs, out, workers=workers, scheduler=scheduler, progress=not no_progress)
    terminal.line("%d trials run, %d already done; results in %s" % (ran, len(specs) - ran, out))


@plot.command("uav")
@click.argument("results", type=click.Path(exists=True, file_okay=False))
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Folder for the PNG files.")
@click.option("--tau", default=20.0, show_default=True, type=FiniteFloat(min=0, min_open=True),
              help="Inter-arrival mean of Figures 17, 18 and 20.")
def plot_uav(results, out, tau):
    """Drone delivery: the seed's Figures 16-20 (and a summary table) from sweep results."""
    need_studies_extra()
    from .drone_delivery import plots
    paths, missing = plots.draw_all(results, out, tau=tau)
    for path in paths:
        terminal.line(path)
    for text in missing:
        terminal.note("uav: %s: give --tau one of them" % text)


COMMANDS = (sim, sweep, plot)
__all__ = ["sim", "sweep", "plot", "COMMANDS"]


@click.group()
def bounds():
    """Print a study's theoretical bounds."""


@bounds.command("energy")
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


from . import energy_commands  # noqa: E402,F401  (registers `sim|sweep|plot energy`)
