"""A sweep runs exactly the seeds its study's `sim` takes, checked whole before any trial runs, with
bounded runs and local processes. Before: `sweep energy --first-seed 2147483647 --runs 2` ended in a ValueError traceback from the
grid, `sweep uav` ran seeds past the 32-bit range `sim uav --seed` refuses, and seed 0 had ARGoS
seed itself from the clock, so that an energy trial did not repeat."""

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.cli.options import SEED_MAX
from swarmvm.studies.drone_delivery import sweep as uav_sweep
from swarmvm.studies.energy_replenishment import sweep as energy_sweep
from swarmvm.studies.energy_replenishment.params import MAX_SEED, MIN_SEED

# study: (its sweep module, the smallest and largest seed, options that keep the grid small)
STUDIES = {"uav": (uav_sweep, 0, SEED_MAX, ["--rules", "", "--thresholds", "0.5", "--taus", "20"]),
           "energy": (energy_sweep, MIN_SEED, MAX_SEED, ["--figures", "9"])}


def seed_option(verb: str, study: str):
    command = main.commands[verb].get_command(None, study)
    return next(p for p in command.params if p.name == ("seed" if verb == "sim" else "first_seed"))


@pytest.mark.parametrize("study", STUDIES)
def test_sim_and_sweep_take_the_same_seeds(study):
    _, smallest, largest, _ = STUDIES[study]
    for verb in ("sim", "sweep"):
        kind = seed_option(verb, study).type
        assert (kind.min, kind.max) == (smallest, largest), verb


def cases():
    for study, (_, smallest, largest, _) in STUDIES.items():
        for first in (smallest - 1, smallest, largest - 2, largest - 1, largest, largest + 1):
            for runs in (1, 2, 3):
                yield study, first, runs


@pytest.mark.parametrize("study,first,runs", list(cases()))
def test_a_sweep_runs_its_seeds_or_refuses_in_one_line(study, first, runs, monkeypatch, tmp_path):
    module, smallest, largest, narrow = STUDIES[study]
    ran = []
    monkeypatch.setattr(module, "sweep", lambda specs, out, **_: ran.extend(specs) or len(specs))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["sweep", study, "-o", str(out), "--first-seed", str(first), "--runs", str(runs),
                                       "--no-progress", *narrow])
    seeds = range(first, first + runs)
    if smallest <= first and seeds[-1] <= largest:
        assert result.exit_code == 0, result.output
        assert sorted({spec.seed for spec in ran}) == list(seeds)
    else:
        assert result.exit_code == 2 and result.output.count("\n") == 1, result.output
        assert result.output.startswith("swarmvm: error: --first-seed: ")
        assert ran == [] and not out.exists()


def test_an_energy_trial_is_never_seeded_from_the_clock():
    result = CliRunner().invoke(main, ["sim", "energy", "--seed", "0"])
    assert result.exit_code == 2
    assert result.output == "swarmvm: error: --seed: 0 is not in the range %d<=x<=%d.\n" % (MIN_SEED, MAX_SEED)


@pytest.mark.parametrize("study", STUDIES)
def test_runs_are_bounded_before_the_grid_is_listed(study, monkeypatch, tmp_path):
    """--runs 1000000000 listed every trial's Params before the first ran, until memory ran out."""
    from swarmvm.studies.sweep_options import MAX_RUNS
    module, _, _, narrow = STUDIES[study]
    monkeypatch.setattr(module, "sweep", lambda specs, out, **_: len(specs))
    base = ["sweep", study, "-o", str(tmp_path / "out"), "--no-progress", *narrow, "--runs"]
    assert CliRunner().invoke(main, base + [str(MAX_RUNS)]).exit_code == 0
    result = CliRunner().invoke(main, base + [str(MAX_RUNS + 1)])
    assert result.exit_code == 2
    assert result.output == "swarmvm: error: --runs: %d is not in the range 1<=x<=%d.\n" % (MAX_RUNS + 1, MAX_RUNS)


def test_local_processes_are_bounded_and_never_more_than_the_trials(monkeypatch, tmp_path):
    """--workers 100000 forked a process per worker before the first trial; now at most 1,024 are
    taken, and a pool never has more processes than trials to run."""
    import multiprocessing

    from swarmvm.studies import sweeps
    from swarmvm.studies.sweep_options import MAX_PROCESSES
    started, real_pool = [], multiprocessing.Pool

    def pool(processes, **options):
        started.append(processes)
        return real_pool(processes, **options)
    monkeypatch.setattr(sweeps.multiprocessing, "Pool", pool)
    base = ["sweep", "uav", "-o", str(tmp_path / "out"), "--no-progress", "--rules", "least-confident",
            "--thresholds", "", "--taus", "20", "--runs", "2", "--weeks", "1", "--week-s", "1000", "--drones", "2",
            "--accuracy-samples", "5", "--workers"]
    result = CliRunner().invoke(main, base + [str(MAX_PROCESSES)])
    assert result.exit_code == 0, result.output
    assert started == [2]
    resumed = CliRunner().invoke(main, base + ["2"])      # all done: no pool (one of 0 processes raised)
    assert resumed.exit_code == 0 and "0 trials run, 2 already done" in resumed.output, resumed.output
    assert started == [2]
    refused = CliRunner().invoke(main, base + [str(MAX_PROCESSES + 1)])
    assert refused.exit_code == 2
    assert refused.output == "swarmvm: error: --workers: %d is not in the range 1<=x<=%d.\n" % (
        MAX_PROCESSES + 1, MAX_PROCESSES)
