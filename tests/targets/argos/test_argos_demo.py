"""`make argos-demo` (firmware/argos_demo.py) reads as what it is: the first run, whose generated
checks are stubs, fires no event, and the demo says that this is expected (issue 27, point 10:
"0 events fired" alone read like a failure)."""

import subprocess
import sys

import pytest
from checkout import EXAMPLE, FIRMWARE

pytestmark = pytest.mark.emulator   # runs real ARGoS


def test_the_first_run_says_its_zero_events_are_expected(argos_prefix, tmp_path):
    run = subprocess.run([sys.executable, str(FIRMWARE / "argos_demo.py"), "--example", str(EXAMPLE),
                          "--name", "energy_worker", "--out", str(tmp_path / "demo")],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    first = run.stdout.split("\n== ")[0].splitlines()
    assert [line.split(": ", 1)[1] for line in first if line.startswith("ep")] == \
        ["300 steps, 0 events fired, 0 violations"] * 6
    assert first[-1].startswith("   as expected, no event fires: the generated checks (energy_worker_controller.cpp)"
                                " return false until they read the sensors")
