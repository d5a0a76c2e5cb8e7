"""The energy-replenishment bounds (studies/energy_replenishment/bounds.py) on design/STUDIES.md's
worked check, the mobile-charger analysis's regimes, and `swarmvm bounds energy`."""

import json

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.studies.energy_replenishment.bounds import (MobileRates, Rates, best_transfer_period,
                                                          constant_supply_bound, fixed_bound, mobile_bound)


def test_fixed_bound_is_the_worked_check():
    b = fixed_bound(Rates())
    assert b.commute_s == pytest.approx(8.333, abs=1e-3)
    assert b.work_s == pytest.approx(78.57, abs=0.01) and b.charge_s == pytest.approx(10.05, abs=0.01)
    assert b.cycle_s == pytest.approx(105.29, abs=0.01) and b.duty_cycle == pytest.approx(0.7462, abs=1e-4)
    assert round(b.work) == 26865 and round(100 * b.efficiency, 1) == 78.1


def test_constant_supply_is_the_worked_check():
    b = constant_supply_bound(Rates())
    assert b.duty_cycle == pytest.approx(0.9045, abs=1e-4) and int(b.work) == 32563


def test_seed_figures_as_fractions_of_the_bound():
    """The seed's 24,943 units are 92.8 % of the bound, its 68.2 % efficiency 12.6 % below it."""
    b = fixed_bound(Rates())
    assert round(100 * 24943 / b.work, 1) == 92.8
    assert round(100 * (1 - 0.682 / b.efficiency), 1) == 12.6


def test_a_commute_longer_than_a_charge_lasts_is_refused():
    with pytest.raises(ValueError, match="cannot reach the work region"):
        fixed_bound(Rates(capacity=10))


def test_mobile_regimes():
    w, m = Rates(), MobileRates()
    short = mobile_bound(w, m, 5.0)               # the charger comes back before the worker needs it
    assert short.feasible and not short.worker_rests
    assert short.duty_cycle == pytest.approx(constant_supply_bound(w).duty_cycle)
    assert not mobile_bound(w, m, 25.0).feasible   # more than a charger can carry
    lossy = MobileRates(loss=0.5, capacity=60)
    rested = [b for b in (mobile_bound(w, lossy, t / 10) for t in range(1, 60)) if b.feasible and b.worker_rests]
    assert rested and all(b.duty_cycle < short.duty_cycle for b in rested)
    for b in (short, *rested):
        assert 0 < b.efficiency < 1 and b.work == pytest.approx(w.workers * b.duty_cycle * w.duration_s * 10)


def test_best_transfer_period_is_the_longest_of_the_best():
    best = best_transfer_period(Rates(), MobileRates())
    assert best.transfer_s == pytest.approx(10.0) and not best.worker_rests
    assert mobile_bound(Rates(), MobileRates(), 10.1).duty_cycle < best.duty_cycle    # capacity caps the transfer
    assert best_transfer_period(Rates(), MobileRates(capacity=1.0)) is None


def test_the_command():
    result = CliRunner().invoke(main, ["bounds", "energy", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert round(data["work"]) == 26865 and round(data["efficiency"], 3) == 0.781
    mobile = CliRunner().invoke(main, ["bounds", "energy", "--strategy", "mobile", "--transfer-period", "5", "--json"])
    assert mobile.exit_code == 0 and json.loads(mobile.output)["transfer_s"] == 5.0
    bad = CliRunner().invoke(main, ["bounds", "energy", "--capacity", "10"])
    assert bad.exit_code == 2 and bad.output.startswith("swarmvm: error: bounds energy: a worker cannot reach")


@pytest.mark.parametrize("option,value", [("--move-rate", "nan"), ("--work-rate", "inf"), ("--capacity", "nan")])
def test_bounds_refuse_numbers_that_are_not_finite(option, value):
    """nan passed click's ranges and printed nan bounds, inf a misleading refusal."""
    result = CliRunner().invoke(main, ["bounds", "energy", option, value])
    assert result.exit_code == 2 and result.output == "swarmvm: error: %s: %s is not a finite number.\n" % (option, value)


@pytest.mark.parametrize("options", [
    [], ["--strategy", "mobile"],
    ["--strategy", "mobile", "--transfer-loss", "0.3", "--charge-rate", "5", "--transfer-rate", "5"],
    ["--strategy", "mobile", "--charger-capacity", "100", "--work-rate", "2"]])
def test_a_trial_is_measured_against_the_bound_the_command_prints(options):
    """Issue 27, point 12: `sim energy` and the summary table measured mobile chargers against
    the constant supply's efficiency (0.9474, the workers' energy only) while `bounds energy
    --strategy mobile` printed the seed's analysis (0.7773, the chargers' energy counted)."""
    from swarmvm.studies.energy_replenishment.params import Params
    printed = CliRunner().invoke(main, ["bounds", "energy", "--json", *options])
    assert printed.exit_code == 0, printed.output
    printed = json.loads(printed.output)
    given = dict(zip(options[::2], options[1::2]))
    fields = {"--strategy": ("strategy", str), "--transfer-loss": ("transfer_loss", float),
              "--charge-rate": ("charge_rate", float), "--transfer-rate": ("transfer_rate", float),
              "--charger-capacity": ("charger_capacity", float), "--work-rate": ("work_rate", float)}
    trial = Params(**{fields[k][0]: fields[k][1](v) for k, v in given.items()}).bound()
    assert (trial.work, trial.efficiency) == (printed["work"], printed["efficiency"])


def test_mobile_bound_of_a_trial_is_the_seeds_analysis():
    from swarmvm.studies.energy_replenishment.params import Params
    mobile = Params(strategy="mobile").bound()
    assert round(mobile.efficiency, 4) == 0.7773 and int(mobile.work) == 32563    # duty cycle: the constant supply's
    assert Params(strategy="mobile", charger_capacity=1.0).bound() is None        # no transfer period is feasible
