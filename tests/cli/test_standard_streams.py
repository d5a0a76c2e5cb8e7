"""Standard output that cannot be written (issue 37, class 4): a full device, a closed stream, a
pipe whose reader has gone. Every verb ends in one line on stderr and status 1: never a
traceback, and never exit 0 with its output lost (fault injection over the three, for each verb
that prints)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

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
    }


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

