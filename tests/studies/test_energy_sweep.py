"""Sweeps of the energy study: the seed's grids, and the same tidy results whatever runs them
(this process or a Dask LocalCluster), resumable."""

from pathlib import Path

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
    drawn, missing = plots.draw_all(tmp_path / "local", tmp_path / "img1", BASE)
    again, _ = plots.draw_all(tmp_path / "local", tmp_path / "img2", BASE)
    assert [p.read_bytes() for p in drawn] == [p.read_bytes() for p in again]    # deterministic figures
    assert len(drawn) + len(missing) == 5 and "Figure 12" not in missing


def test_sweep_energy_unknown_figure_one_line():
    import subprocess
    import sys
    out = subprocess.run([sys.executable, "-m", "swarmvm", "sweep", "energy", "-o", "x", "--figures", "9,13"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.startswith("swarmvm: error: energy: --figures:") and out.stderr.count("\n") == 1


def test_plot_draws_the_figures_at_the_rates_the_sweep_had(tmp_path):
    """A sweep of Figure 10 at 30 s, its results made up (no ARGoS: the plotting is under test).
    Plotted with the sweep's --duration every figure has trials (each grid holds the base
    configurations); at the default rates (600 s) none has, and each is named on stderr rather
    than drawn empty. The plots filtered on the default rates whatever the sweep had: every
    figure of such a sweep came out empty, with matplotlib's warnings."""
    from click.testing import CliRunner

    from swarmvm.cli.commands import main
    from swarmvm.studies import sweeps
    for p in sweep.grid(BASE, ["10"], seeds=[1, 2]):
        row = dict(key=sweep.trial_key(p), **p.to_dict(), work=100.0 * p.work_rate + p.seed, efficiency=0.5,
                   depleted=0.0, consumed=50.0, lost=1.0, work_of_bound=0.9, bound_efficiency=0.7, seconds=1.0)
        sweeps.write_trial(tmp_path / "grid", row["key"], dict(trials=[row]), sweep.TABLES)
    runner = CliRunner()
    at_sweep = runner.invoke(main, ["plot", "energy", str(tmp_path / "grid"), "-o", str(tmp_path / "img"),
                                    "--duration", "30"])
    assert at_sweep.exit_code == 0 and at_sweep.stderr == "", at_sweep.output
    assert [Path(line).name for line in at_sweep.stdout.split()] == [
        "energy_fig9.png", "energy_fig10.png", "energy_fig11.png", "energy_fig12.png", "energy_summary.csv"]
    at_default = runner.invoke(main, ["plot", "energy", str(tmp_path / "grid"), "-o", str(tmp_path / "img2")])
    assert at_default.exit_code == 0 and at_default.stdout.split() == [str(tmp_path / "img2" / "energy_summary.csv")]
    assert [line.split(": ")[3] for line in at_default.stderr.splitlines()] == [
        "Figure 9", "Figure 10", "Figure 11", "Figure 12"]
