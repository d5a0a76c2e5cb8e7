"""`swarmvm sim|sweep|plot uav`: JSON keys, one-line errors, figures from a sweep."""

import json

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

QUICK = ["--weeks", "1", "--week-s", "4000", "--drones", "5", "--accuracy-samples", "20"]


def test_sim_json_has_the_keys_the_issue_names():
    result = CliRunner().invoke(main, ["sim", "uav", "--json", "--seed", "3", *QUICK])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    for key in ("delivered", "aborted", "pending", "median_delivery_min", "accuracy_by_week"):
        assert key in data
    assert len(data["accuracy_by_week"]) == 2 and data["orders"] == data["delivered"] + data["pending"]


def test_sim_rejects_bad_values_with_one_line():
    result = CliRunner().invoke(main, ["sim", "uav", "--drones", "0"])
    assert result.exit_code == 2
    assert result.output.strip() == "swarmvm: error: --drones: must be at least 1"


@pytest.mark.parametrize("option,value,message", [
    ("--rotors", "0", "must be at least 1"),            # equation 14 divides by them: was a ZeroDivisionError
    ("--disc-m2", "0", "must be positive"), ("--capacity-wh", "0", "must be positive"),
    ("--speed-ms", "0", "must be positive"), ("--battery-kg", "-1", "must be positive"),
    ("--charger-eff", "1.5", "must lie in (0, 1]"),
    ("--tau-min", "inf", "inf is not a finite number."),    # orders never came: the trial never ended
    ("--frame-kg", "nan", "nan is not a finite number.")])
def test_sim_refuses_parameters_the_physics_cannot_take(option, value, message):
    result = CliRunner().invoke(main, ["sim", "uav", option, value, *QUICK])
    assert result.exit_code == 2 and result.output == "swarmvm: error: %s: %s\n" % (option, message)


@pytest.mark.parametrize("option,value,message", [
    ("--taus", "abc", "'abc' is not a valid float."), ("--taus", "20,nan", "nan is not a finite number."),
    ("--taus", "0", "0.0 is not in the range x>0."), ("--thresholds", "0.5,2", "2.0 is not in the range 0<=x<=1.")])
def test_sweep_refuses_grid_values_by_the_option_given(option, value, message, tmp_path):
    result = CliRunner().invoke(main, ["sweep", "uav", "-o", str(tmp_path / "out"), option, value])
    assert result.exit_code == 2 and result.output == "swarmvm: error: %s: %s\n" % (option, message)
    assert not (tmp_path / "out").exists()


def test_sweep_then_plot(tmp_path):
    out = tmp_path / "results"
    args = ["sweep", "uav", "-o", str(out), "--taus", "20", "--runs", "1", "--rules", "least-confident",
            "--thresholds", "0.8", "--no-progress", *QUICK]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "2 trials run, 0 already done" in result.output
    assert "0 trials run, 2 already done" in CliRunner().invoke(main, args).output
    plots = CliRunner().invoke(main, ["plot", "uav", str(out), "-o", str(tmp_path / "img")])
    assert plots.exit_code == 0, plots.output
    names = {line.rsplit("/", 1)[-1] for line in plots.output.split()}
    assert {"uav_fig16_rules.png", "uav_fig17_accuracy.png", "uav_fig18_soh_maps.png", "uav_fig19_threshold.png"} <= names
    again = CliRunner().invoke(main, ["plot", "uav", str(out), "-o", str(tmp_path / "again")])
    assert again.exit_code == 0, again.output
    for name in names:                                   # the figures are deterministic
        assert (tmp_path / "img" / name).read_bytes() == (tmp_path / "again" / name).read_bytes()
    elsewhere = CliRunner().invoke(main, ["plot", "uav", str(out), "-o", str(tmp_path / "at10"), "--tau", "10"])
    assert elsewhere.exit_code == 0, elsewhere.output       # the figures at one tau: none at 10, not drawn empty
    assert {line.rsplit("/", 1)[-1] for line in elsewhere.stdout.split()} == {
        "uav_fig16_rules.png", "uav_fig19_threshold.png", "uav_summary.md"}
    assert elsewhere.stderr.splitlines() == [
        "swarmvm: note: uav: Figure %d: no trials at tau 10 min (the sweep's: 20): give --tau one of them" % n
        for n in (17, 18)]
    bad = CliRunner().invoke(main, ["sweep", "uav", "-o", str(out), "--rules", "fastest"])
    assert bad.exit_code == 2 and bad.output.startswith("swarmvm: error: --rules: unknown rule 'fastest'")


def test_without_the_studies_extra_each_verb_says_how_to_get_it(monkeypatch):
    import importlib.util
    find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "pandas" else find_spec(name, *a))
    for verb in (["sim", "uav"], ["sweep", "uav", "-o", "x"], ["plot", "uav", ".", "-o", "x"]):
        result = CliRunner().invoke(main, verb)
        assert result.exit_code == 2, verb
        assert result.output == 'swarmvm: error: the studies need pandas: pip install "swarmvm[studies]"\n', verb


@pytest.mark.parametrize("options,message", [
    (["--drones", "10001"], "--drones: must be at most 10,000"),
    (["--drones", "10000", "--accuracy-samples", "1001"],
     "--accuracy-samples: 10,000 drones x 1,001 samples pass 10,000,000, the most a trial keeps"),
    (["--weeks", "2000", "--tau-min", "1"],
     "--weeks: about 20,160,000 orders a run (weeks x week-s / tau-min) pass 10,000,000, the most a trial draws"),
    (["--pretrain-weeks", "20000"],
     "--pretrain-weeks: about 10,080,000 orders a run (weeks x week-s / tau-min) pass 10,000,000, the most a trial draws"),
    (["--weeks", "100000000", "--drones", "1000000000"], "--drones: must be at most 10,000")])
def test_sim_refuses_a_trial_too_large_for_memory_before_it_starts(options, message):
    """--drones 100000 --weeks 0 took 11 GB and a minute; a huge --weeks drew its orders until memory ran out."""
    result = CliRunner().invoke(main, ["sim", "uav", *options])
    assert result.exit_code == 2 and result.output == "swarmvm: error: %s\n" % message


def test_the_largest_trials_allowed_are_accepted():
    from swarmvm.studies.drone_delivery.params import MAX_ACCURACY_CELLS, MAX_DRONES, MAX_ORDERS, Params
    Params(drones=MAX_DRONES, accuracy_samples=MAX_ACCURACY_CELLS // MAX_DRONES)
    Params(weeks=MAX_ORDERS * 20 * 60 // Params().week_s, tau_min=20.0)
