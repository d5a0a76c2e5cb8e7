"""Every number a study verb's options accept gives a trial it can run, or is refused in one line
with exit status 2 (never a traceback, a hang, or numbers that mean nothing): each number option
of `sim`, `sweep` and `bounds`, alone, at the ends of its range, just past them and at extreme
magnitudes, for each strategy.

Three passes. With the trial replaced by a stub that records it was reached, every verb: the
options must become parameters or a one-line refusal. Then the trials for real, small (warnings
as errors, a time limit): the drone trial in-process, the energy trial in real ARGoS, `bounds
energy` (arithmetic). Options in range alone may not be together (a drain, a charge, a flight,
an energy total past floating point or the integer ticks): the parameters must refuse those."""

from __future__ import annotations

import math
import signal
import warnings
from collections.abc import Iterator

import click
import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.cli.options import FiniteFloat
from swarmvm.studies.drone_delivery import engine as uav_engine, sweep as uav_sweep
from swarmvm.studies.energy_replenishment import sweep as energy_sweep, trial as energy_trial

HUGE = 10 ** 18
MOBILE = ["--strategy", "mobile", "--chargers", "2"]


class Reached(Exception):
    """The stub trial was called: the options made parameters it takes."""


def reached(*_args, **_kwargs):
    raise Reached()


# verb, study, the stubs that stand for its trial, and the options every call of it is given
# (OUT: a folder in the test's tmp_path).
COMMANDS = [("sim", "uav", [(uav_engine, "run")], []),
            ("sim", "energy", [(energy_trial, "run")], []),
            ("sim", "energy", [(energy_trial, "run")], MOBILE),
            ("sweep", "uav", [(uav_sweep, "sweep")], ["-o", "OUT", "--rules", "", "--thresholds", "0.5", "--taus", "20"]),
            ("sweep", "energy", [(energy_sweep, "sweep")], ["-o", "OUT", "--figures", ",".join(energy_sweep.FIGURES)]),
            ("bounds", "energy", [], []),
            ("bounds", "energy", [], ["--strategy", "mobile"])]


def extremes(kind: click.ParamType) -> list[str]:
    """The values to try for an option of this type."""
    if isinstance(kind, click.IntRange):
        ends = [kind.min, kind.max]
        values = {0, 1, -1, HUGE, -HUGE} | {end + step for end in ends if end is not None for step in (-1, 0, 1)}
        return [str(v) for v in sorted(values)]
    if isinstance(kind, FiniteFloat):
        ends = [end for end in (kind.min, kind.max) if end is not None]
        values = {0.0, -0.0, 5e-324, 1e-300, 1.0, -1.0, 1e300, -1e300, 1.7976931348623157e308}
        values |= {v for end in ends for v in (end, math.nextafter(end, -math.inf), math.nextafter(end, math.inf),
                                               end - 1, end + 1)}
        return [repr(v) for v in sorted(values)]
    if kind == click.INT:
        return [str(v) for v in (-HUGE, -1, 0, 1, HUGE)]
    return []


def cases(verb: str, study: str | None = None) -> Iterator[tuple]:
    """(verb, study, stubs, given options, option, value) for every number option's extremes."""
    for command_verb, command_study, stubs, given in COMMANDS:
        if command_verb != verb or study not in (None, command_study):
            continue
        for param in main.commands[verb].get_command(None, command_study).params:
            if isinstance(param, click.Option) and not param.is_flag and max(param.opts, key=len) not in given:
                for value in extremes(param.type):
                    yield command_verb, command_study, stubs, given, max(param.opts, key=len), value


def case_id(case: tuple) -> str:
    verb, study, _, given, option, value = case
    return " ".join([verb, study, *given[:2], option, value])


def one_line_refusal(output: str) -> bool:
    return output.startswith("swarmvm: error: ") and output.count("\n") == 1


def over_time(*_args):
    raise TimeoutError("ran over 60 s")


def invoke(args: list[str]):
    """The command in this process, warnings as errors, 60 s at most (a child it started, such
    as ARGoS, is killed by subprocess.run when the alarm interrupts it)."""
    signal.signal(signal.SIGALRM, over_time)
    signal.alarm(60)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            return CliRunner().invoke(main, args)
    finally:
        signal.alarm(0)


@pytest.mark.parametrize("case", [*cases("sim"), *cases("sweep")], ids=case_id)
def test_a_value_reaches_the_trial_or_is_one_line(case, monkeypatch, tmp_path):
    verb, study, stubs, given, option, value = case
    for module, name in stubs:
        monkeypatch.setattr(module, name, reached)
    given = [str(tmp_path / "out") if arg == "OUT" else arg for arg in given]
    result = CliRunner().invoke(main, [verb, study, *given, option, value])
    if result.exit_code == 2:
        assert one_line_refusal(result.output), result.output
        assert not (tmp_path / "out").exists()
    else:
        assert isinstance(result.exception, Reached), (result.output, result.exception)


# Small trials: what the extremes are judged in (an option given in the case replaces these).
SMALL = {"uav": {"--weeks": "1", "--week-s": "2000", "--drones": "3", "--accuracy-samples": "10"},
         "energy": {"--duration": "10"}}


def real_cases() -> Iterator[tuple]:
    for case in cases("sim"):
        if not (case[4] == "--duration" and float(case[5]) > 3600):   # long trials, up to 13 years: not run here
            yield case
    yield "sim", "uav", [], ["--air-density", "5e-324"], "--disc-m2", "5e-324"   # their product is 0
    yield "sim", "uav", [], ["--capacity-wh", "1e308"], "--charger-w", "5e-324"
    yield "sim", "uav", [], ["--d-min-m", "1e300", "--d-max-m", "1e300"], "--speed-ms", "1e300"


@pytest.mark.parametrize("case", list(real_cases()), ids=case_id)
def test_a_real_trial_at_the_extremes_runs_or_is_one_line(case):
    verb, study, _, given, option, value = case
    small = [text for pair in SMALL[study].items() if pair[0] != option for text in pair]
    result = invoke([verb, study, "--json", *small, *given, option, value])
    if result.exit_code == 2:
        assert one_line_refusal(result.output), result.output
    else:
        assert result.exit_code == 0 and result.output.startswith("{"), (result.output, result.exception)


@pytest.mark.parametrize("tau", ["5e-324", "0.0001", "1e300"])
@pytest.mark.parametrize("weeks", ["0", "100", "1000000"])
def test_a_uav_sweep_tau_reaches_the_trial_or_is_one_line(tau, weeks, monkeypatch, tmp_path):
    """The grid makes a trial's parameters from each --taus value and the other options: a tau
    they cannot take together (too many orders) was a ValueError traceback."""
    monkeypatch.setattr(uav_sweep, "sweep", reached)
    result = CliRunner().invoke(main, ["sweep", "uav", "-o", str(tmp_path / "out"), "--taus", tau, "--weeks", weeks])
    if result.exit_code == 2:
        assert one_line_refusal(result.output), result.output
        assert result.output.startswith("swarmvm: error: --%s: " % ("weeks" if tau != "1e300" else "taus")), result.output
    else:
        assert isinstance(result.exception, Reached), (result.output, result.exception)


@pytest.mark.parametrize("case", list(cases("bounds")), ids=case_id)
def test_bounds_energy_answers_or_refuses_in_one_line(case):
    verb, study, _, given, option, value = case
    result = invoke([verb, study, *given, option, value, "--json"])
    if result.exit_code == 2:
        assert one_line_refusal(result.output), result.output
    else:
        assert result.exit_code == 0 and result.output.startswith("{"), (result.output, result.exception)
