"""`swarmvm footprint` when its standard output cannot be written (issue 37, class 4): the same
three faults as every other verb's (tests/cli/test_standard_streams.py), here where a linked
robot image is built."""

import os

import pytest

from cli.test_standard_streams import REASONS, run
from footprint_images import elf


@pytest.mark.parametrize("fault", sorted(REASONS))
def test_footprint_ends_a_stdout_failure_in_one_line(build, fault):
    if fault == "full" and not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    result = run(["footprint", str(elf(build, "kilobot", "energy_worker"))], fault)
    assert result.returncode == 1, result.stderr
    assert result.stderr.splitlines()[-1:] == ["swarmvm: error: standard output: cannot write (%s)" % REASONS[fault]]
    assert "Traceback" not in result.stderr and "Exception ignored" not in result.stderr, result.stderr
