"""Standard output that cannot be written (issue 37, class 4): a full device, a closed stream, a
pipe whose reader has gone. Every verb ends in one line on stderr and status 1: never a
traceback, and never exit 0 with its output lost (fault injection over the three, for each verb
that prints)."""

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import click
import pytest

from swarmvm.cli.commands import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
SYNTHESIS = ROOT / "tests" / "corpus" / "synthesis" / "energy_worker"


def verbs(tmp: Path) -> dict[str, list[str]]:
    """Each verb that prints on stdout, with arguments that make it print."""
    script = tmp / "s.txt"
    script.write_text(subprocess.run([sys.executable, "-m", "swarmvm", "script", str(EXAMPLE), "--steps", "5"],
                                     capture_output=True, text=True, check=True).stdout)
    trace = tmp / "r.trace"
    trace.write_text(subprocess.run([sys.executable, "-m", "swarmvm", "trace", str(EXAMPLE), "--script", str(script)],
                                    capture_output=True, text=True, check=True).stdout)
    return {
        "help": ["--help"], "version": ["--version"], "verb help": ["gen", "--help"],
        "check": ["check", str(EXAMPLE)], "check --properties": ["check", "--properties", str(EXAMPLE)],
        "pack": ["pack", str(EXAMPLE), "-o", str(tmp / "x.svm")],
        "gen": ["gen", str(EXAMPLE), "--target", "python", "-o", str(tmp / "py")],
        "script": ["script", str(EXAMPLE), "--steps", "2000"],
        "trace": ["trace", str(EXAMPLE), "--script", str(script)],
        "equiv": ["equiv", str(EXAMPLE), str(EXAMPLE)],
        "export": ["export", str(EXAMPLE), "--format", "yaml", "-o", str(tmp / "x.yaml")],
        "synth": ["synth", *map(str, sorted(SYNTHESIS.glob("*.nza"))), "--script", str(SYNTHESIS / "script.lua"),
                  "-o", str(tmp / "synth.yaml")],
        "inspect": ["inspect", str(EXAMPLE), str(trace), "-o", str(tmp / "page.html")],
        "bounds energy": ["bounds", "energy"], "cmake-dir": ["cmake-dir"],
        "compat-switch": ["compat-switch", str(_published_layout(tmp)), "--variant", "default"],
    } | ({
        "sim uav": ["sim", "uav", *QUICK_UAV],
        "sweep uav": ["sweep", "uav", "-o", str(tmp / "sweep"), "--rules", "random", "--thresholds", "",
                      "--taus", "20", "--runs", "1", "--no-progress", *QUICK_UAV],
        "plot uav": ["plot", "uav", str(_uav_results(tmp)), "-o", str(tmp / "figures")],
    } if STUDIES else {})


# The study verbs need the studies extra; the wheel's own check runs these tests without it and
# checks the study verbs' one-line refusal itself (scripts/check_wheel.sh).
STUDIES = all(importlib.util.find_spec(name) for name in ("numpy", "pandas", "pyarrow", "dask", "tqdm", "matplotlib"))


# Verbs whose fault injection lives elsewhere, with why: each needs what only another folder builds.
ELSEWHERE = {
    "footprint": "a linked robot image: tests/footprint/test_footprint_streams.py",
    "sim energy": "real ARGoS and a 600-s trial: the energy study's tests run it",
    "sweep energy": "real ARGoS, many trials",
    "plot energy": "an energy sweep's results",
}
QUICK_UAV = ["--weeks", "1", "--week-s", "3600", "--drones", "3"]


def _published_layout(tmp: Path) -> Path:
    """A copy of a published OpenSwarm project's build files, for compat-switch to edit."""
    folder = tmp / "openswarm"
    shutil.copytree(ROOT.parent / "shared" / "reference" / "openswarm-layouts" / "energy", folder)
    return folder


def _uav_results(tmp: Path) -> Path:
    """A one-trial drone sweep, for plot to draw from."""
    results = tmp / "uav_results"
    subprocess.run([sys.executable, "-m", "swarmvm", "sweep", "uav", "-o", str(results), "--rules", "random",
                    "--thresholds", "", "--taus", "20", "--runs", "1", "--no-progress", *QUICK_UAV],
                   capture_output=True, text=True, check=True)
    return results


def _commands(group: click.Group, prefix: str = "") -> set[str]:
    """Every verb of the command line, a group's as "group verb" (the study verbs list theirs
    when asked, so the walk asks as click does)."""
    names = set()
    context = click.Context(group)
    for name in group.list_commands(context):
        command = group.get_command(context, name)
        if isinstance(command, click.Group):
            names |= _commands(command, prefix + name + " ")
        else:
            names.add(prefix + name)
    return names


def test_every_verb_is_fault_injected(tmp_path):
    """A new verb without a case here (or a reason it is elsewhere) fails: "every verb" stays true."""
    commands = _commands(main)
    assert {"check", "gen", "bounds energy", "sim uav"} <= commands      # the walk sees verbs and groups' verbs
    without_extra = set() if STUDIES else {"sim uav", "sweep uav", "plot uav"}
    assert commands - set(verbs(tmp_path)) - set(ELSEWHERE) - without_extra == set()


def _closed() -> None:
    os.close(1)


def run(args: list[str], fault: str) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "swarmvm", *args]
    if fault == "full":
        with open("/dev/full", "wb") as full:
            return subprocess.run(command, stdout=full, stderr=subprocess.PIPE, text=True, timeout=300)
    if fault == "closed":
        return subprocess.run(command, stderr=subprocess.PIPE, text=True, timeout=300, preexec_fn=_closed)
    read, write = os.pipe()
    os.close(read)                     # the reader is gone before the first line
    try:
        return subprocess.run(command, stdout=write, stderr=subprocess.PIPE, text=True, timeout=300)
    finally:
        os.close(write)


REASONS = {"full": "No space left on device", "closed": "closed", "broken": "Broken pipe"}


@pytest.mark.parametrize("fault", sorted(REASONS))
def test_every_verb_ends_a_stdout_failure_in_one_line(fault, tmp_path):
    if fault == "full" and not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    for name, args in verbs(tmp_path).items():
        result = run(args, fault)
        assert result.returncode == 1, (name, result.returncode, result.stderr)
        assert result.stderr.splitlines()[-1:] == ["swarmvm: error: standard output: cannot write (%s)"
                                                   % REASONS[fault]], (name, result.stderr)
        assert "Traceback" not in result.stderr and "Exception ignored" not in result.stderr, (name, result.stderr)

