"""Sweeps: tidy Parquet results, resumable (finished trials are not rerun), and the same results
whatever runs them: this process, two local processes, or a Dask LocalCluster."""

import pandas as pd
import pytest

from swarmvm.studies.drone_delivery import sweep
from swarmvm.studies.drone_delivery.params import Params

BASE = Params(weeks=2, week_s=5400, drones=6, accuracy_samples=20)


def specs():
    return sweep.grid(BASE, rules=["least-confident", "most-confident"], thresholds=[0.8], taus=[10], seeds=[1, 2])


def frames_without_timing(out):
    frames = sweep.load(out)
    frames["trials"] = frames["trials"].drop(columns=["seconds", "cpu_seconds"])
    return frames


def assert_same(a, b):
    for table in sweep.TABLES:
        pd.testing.assert_frame_equal(a[table], b[table])


def test_grid_covers_rules_thresholds_taus_and_seeds():
    grid = sweep.grid(BASE)
    assert len(grid) == (3 + 6) * 6 * 20
    assert len({sweep.trial_key(p) for p in grid}) == len(grid)


def test_results_are_tidy_and_the_sweep_resumes(tmp_path):
    assert sweep.sweep(specs(), tmp_path, progress=False) == 6
    frames = sweep.load(tmp_path)
    assert len(frames["trials"]) == 6 and len(frames["accuracy"]) == 6 * 3 * 6
    assert len(frames["backlog"]) == 6 * 2 and len(frames["drones"]) == 6 * 6
    assert set(frames["trials"]["rule"]) == {"least-confident", "most-confident", "threshold"}
    assert sweep.sweep(specs(), tmp_path, progress=False) == 0        # nothing left to do
    victim = sorted((tmp_path / "trials").glob("*.parquet"))[0]
    victim.unlink()
    assert sweep.sweep(specs(), tmp_path, progress=False) == 1        # only the missing trial
    summary = sweep.summarise(sweep.load(tmp_path))
    assert len(summary) == 3 and set(summary["runs"]) == {2}


@pytest.mark.slow
def test_two_local_processes_give_identical_results(tmp_path):
    sweep.sweep(specs(), tmp_path / "one", workers=1, progress=False)
    sweep.sweep(specs(), tmp_path / "two", workers=2, progress=False)
    assert_same(frames_without_timing(tmp_path / "one"), frames_without_timing(tmp_path / "two"))


@pytest.mark.slow
def test_a_dask_cluster_gives_identical_results(tmp_path):
    from distributed import Client, LocalCluster
    sweep.sweep(specs()[:3], tmp_path / "local", progress=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            assert sweep.sweep(specs()[:3], tmp_path / "dask", scheduler=client, progress=False) == 3
        assert sweep.sweep(specs()[:3], tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False) == 0
    assert_same(frames_without_timing(tmp_path / "local"), frames_without_timing(tmp_path / "dask"))
