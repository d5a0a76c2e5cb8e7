"""Issue 27: the distributed sweeps on a real Dask cluster, started the way a user starts one
(docs/studies/drone-delivery.md, "On a Dask cluster"): a ``dask scheduler`` process and two
``dask worker`` processes, each worker with its own local directory, ports chosen free, and
``swarmvm sweep uav --scheduler ADDRESS`` connecting by address. The results must be those of a
local run. The other sweep tests use a LocalCluster, whose workers share this process's set-up;
here the workers are separate programs that import swarmvm themselves. The processes are
stopped however the test ends."""

import socket
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.studies.drone_delivery import sweep

DASK = str(Path(sys.executable).with_name("dask"))
GRID = ["--taus", "20", "--runs", "2", "--rules", "least-confident", "--thresholds", "0.8", "--no-progress",
        "--weeks", "1", "--week-s", "4000", "--drones", "5", "--accuracy-samples", "20"]


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and two workers as separate processes; yields the scheduler's address."""
    address = "tcp://127.0.0.1:%d" % free_port()
    commands = [[DASK, "scheduler", "--host", "127.0.0.1", "--port", address.rsplit(":", 1)[1], "--no-dashboard"]]
    commands += [[DASK, "worker", address, "--nworkers", "1", "--nthreads", "1", "--no-dashboard",
                  "--local-directory", str(tmp_path / name)] for name in ("worker1", "worker2")]
    processes = []
    try:
        for command in commands:
            processes.append(subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        from distributed import Client
        with Client(address, timeout=60) as client:
            client.wait_for_workers(2, timeout=120)
            workers = client.scheduler_info()["workers"].values()
            assert len({w["local_directory"] for w in workers}) == 2
        yield address
    finally:
        for process in reversed(processes):
            process.terminate()
        for process in reversed(processes):
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def tables(out):
    frames = sweep.load(out)
    frames["trials"] = frames["trials"].drop(columns=["seconds", "cpu_seconds"])
    return frames


@pytest.mark.slow
def test_a_sweep_on_a_dask_cluster_gives_the_local_results(cluster, tmp_path):
    runner = CliRunner()
    local = runner.invoke(main, ["sweep", "uav", "-o", str(tmp_path / "local"), *GRID])
    assert local.exit_code == 0, local.output
    remote = runner.invoke(main, ["sweep", "uav", "-o", str(tmp_path / "dask"), "--scheduler", cluster, *GRID])
    assert remote.exit_code == 0, remote.output
    assert "4 trials run, 0 already done" in remote.output
    local_tables, dask_tables = tables(tmp_path / "local"), tables(tmp_path / "dask")
    for table in sweep.TABLES:
        assert len(local_tables[table]) > 0
        pd.testing.assert_frame_equal(local_tables[table], dask_tables[table])
    again = runner.invoke(main, ["sweep", "uav", "-o", str(tmp_path / "dask"), "--scheduler", cluster, *GRID])
    assert "0 trials run, 4 already done" in again.output                 # resumed on the cluster too
