"""Sweeps of the energy study: the seed's grids, and the same tidy results whatever runs them
(this process or a Dask LocalCluster), resumable."""

import pandas as pd
import pytest

from swarmvm.studies.energy_replenishment import plugin, sweep
from swarmvm.studies.energy_replenishment.params import Params

BASE = Params(duration_s=30.0)


def test_figure9_grid():
    grid = sweep.grid(Params(), ["9"], seeds=range(1, 51))
    assert len(grid) == (1 + 7 * 5) * 50 == 1800
    assert len({sweep.trial_key(p) for p in grid}) == len(grid)
    mobile = {(p.chargers, p.charger_capacity) for p in grid if p.strategy == "mobile"}
    assert mobile == {(n, phi * 100) for n in (1, 2, 4, 6, 8, 10, 12) for phi in (1, 1.5, 2, 4, 6)}


def test_shared_configurations_run_once():
    every = sweep.grid(Params(), seeds=[1])
    assert len(every) == len({sweep.trial_key(p) for p in every}) == 36 + 9 + 9 + 9 - 3
    assert sum(p.strategy == "fixed" for p in every) == 1 + 4 + 4   # Figure 12's fixed is Figure 9's


def test_unknown_figure():
    with pytest.raises(ValueError):
        sweep.figure_cases("13", Params())


def specs():
    return sweep.grid(BASE, ["12"], seeds=[1, 2])[:4]


def without_timing(out):
    return sweep.load(out).drop(columns=["seconds"])


@pytest.mark.emulator
@pytest.mark.slow
def test_local_and_dask_give_identical_results(tmp_path):
    try:
        plugin.find_argos()
    except plugin.BuildError as exc:
        pytest.skip(str(exc))
    from distributed import Client, LocalCluster
    assert sweep.sweep(specs(), tmp_path / "local", progress=False) == 4
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            assert sweep.sweep(specs(), tmp_path / "dask", scheduler=client, progress=False) == 4
    local = without_timing(tmp_path / "local")
    assert len(local) == 4 and set(local["strategy"]) == {"fixed", "mobile"}
    pd.testing.assert_frame_equal(local, without_timing(tmp_path / "dask"))
    assert sweep.sweep(specs(), tmp_path / "local", progress=False) == 0          # resumed: nothing left
    next((tmp_path / "local" / "trials").glob("*.parquet")).unlink()
    assert sweep.sweep(specs(), tmp_path / "local", progress=False) == 1          # only the missing trial
    from swarmvm.studies.energy_replenishment import plots
    first = [p.read_bytes() for p in plots.draw_all(tmp_path / "local", tmp_path / "img1")]
    second = [p.read_bytes() for p in plots.draw_all(tmp_path / "local", tmp_path / "img2")]
    assert len(first) == 5 and first == second                                  # deterministic figures


def test_sweep_energy_unknown_figure_one_line():
    import subprocess
    import sys
    out = subprocess.run([sys.executable, "-m", "swarmvm", "sweep", "energy", "-o", "x", "--figures", "9,13"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.startswith("swarmvm: error: energy: --figures:") and out.stderr.count("\n") == 1
