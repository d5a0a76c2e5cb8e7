"""`sweep --scheduler ADDRESS`: a scheduler that is not there, or an address that is not one, is
one line naming --scheduler and what Dask said, exit status 2, before any trial is counted and
without a results folder. Before, both were tracebacks (OSError after 30 s, ValueError)."""

import os
import socket
import subprocess
import sys

import pytest

UAV = ["sweep", "uav", "--runs", "1", "--rules", "least-confident", "--thresholds", "", "--taus", "20",
       "--weeks", "1", "--week-s", "1000", "--drones", "2"]
ENERGY = ["sweep", "energy", "--runs", "1", "--figures", "12", "--duration", "1"]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def sweep(args: list[str], tmp_path):
    # Dask's connect timeout shortened from 30 s: what is tested is what comes after it.
    env = dict(os.environ, DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT="2s")
    return subprocess.run([sys.executable, "-m", "swarmvm", *args, "-o", str(tmp_path / "out")],
                          capture_output=True, text=True, env=env, timeout=120)


@pytest.mark.parametrize("args", [UAV, ENERGY], ids=["uav", "energy"])
def test_an_address_that_is_not_one(args, tmp_path):
    result = sweep([*args, "--scheduler", "not an address"], tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.endswith("--scheduler: missing port number in address 'not an address'\n")
    assert result.stderr.count("\n") == 1 and not (tmp_path / "out").exists()


def test_a_scheduler_that_is_not_there(tmp_path):
    address = "tcp://127.0.0.1:%d" % free_port()
    result = sweep([*UAV, "--scheduler", address], tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.startswith("swarmvm: error: --scheduler: Timed out trying to connect to %s" % address)
    assert result.stderr.count("\n") == 1 and not (tmp_path / "out").exists()
