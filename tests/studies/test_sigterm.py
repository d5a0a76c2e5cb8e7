"""SIGTERM (a scheduler's or `timeout`'s stop) ends a verb with what it started: `sim energy`'s
ARGoS child is killed and its temporary folder removed; a local sweep's worker processes end.
Before, the process ended at once and ARGoS (or the sweep's workers) ran on, orphaned."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path


def children(pid: int) -> set[int]:
    """The processes ``pid`` started (Linux /proc)."""
    return {int(child) for child in Path("/proc/%d/task/%d/children" % (pid, pid)).read_text().split()}


def alive(pid: int) -> bool:
    try:
        return Path("/proc/%d/stat" % pid).read_text().split(") ")[1][0] != "Z"   # not a zombie
    except FileNotFoundError:
        return False


def wait_for(predicate, seconds: float):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        found = predicate()
        if found:
            return found
        time.sleep(0.1)
    return predicate()


def terminate(args: list[str], started, tmp_path: Path) -> tuple[int, set[int]]:
    """Runs swarmvm with ``args``; once ``started(pid)`` names the processes it started, SIGTERM
    to swarmvm. Returns its exit status and those processes."""
    env = dict(os.environ, TMPDIR=str(tmp_path))
    proc = subprocess.Popen([sys.executable, "-m", "swarmvm", *args], env=env, cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    try:
        started_ones = wait_for(lambda: started(proc.pid), 300)
        assert started_ones, "nothing started"
        proc.send_signal(signal.SIGTERM)
        status = proc.wait(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    return status, started_ones


def test_sim_energy_stops_argos_and_removes_its_folder(tmp_path):
    def argos(pid):
        return {c for c in children(pid) if Path("/proc/%d/exe" % c).resolve().name == "argos3"}
    status, started = terminate(["sim", "energy", "--duration", "1000000"], argos, tmp_path)
    assert status == -signal.SIGTERM
    assert not wait_for(lambda: [pid for pid in started if alive(pid)], 10), "ARGoS ran on"
    assert not list(tmp_path.glob("swarmvm-energy-*"))


def catches_sigterm(pid: int) -> bool:
    """Whether ``pid`` runs a handler of SIGTERM (its SigCgt mask, /proc/PID/status)."""
    try:
        status = Path("/proc/%d/status" % pid).read_text()
    except FileNotFoundError:
        return False
    caught = int(next(line for line in status.splitlines() if line.startswith("SigCgt:")).split()[1], 16)
    return bool(caught >> (signal.SIGTERM - 1) & 1)


def test_a_local_sweep_ends_its_workers(tmp_path):
    def workers(pid):
        """The pool's two workers, once both are past their start (SIGTERM's default action
        again: the verb's handler, which they are forked with, would unwind the verb in them)."""
        found = children(pid)
        return found if len(found) >= 2 and not any(catches_sigterm(c) for c in found) else set()
    status, started = terminate(["sweep", "uav", "-o", "out", "--workers", "2", "--rules", "least-confident",
                                 "--thresholds", "", "--taus", "20", "--runs", "4", "--no-progress"],
                                workers, tmp_path)
    assert status == -signal.SIGTERM
    assert not wait_for(lambda: [pid for pid in started if alive(pid)], 10), "the workers ran on"
