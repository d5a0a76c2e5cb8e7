"""The C++ VM steps by composed state where it can (every check bound, no action on an input,
no violation hook) and the general way otherwise; both must fire the same events and reach the
same states and violation counts, under every option, on every corpus supervisor (the composed
step itself is checked against the Python reference by tests/conformance/test_cpp.py)."""

import subprocess
from pathlib import Path

import pytest

from conformance.cases import SUPERVISORS
from conformance.cpp_harness import build_program
from swarmvm.compiler.pipeline import compile_inputs

PROGRAM = Path(__file__).resolve().parent / "step_paths.cpp"
OPTIONS = ["%s %s %s" % (i, c, p) for i in ("level", "edge") for c in ("after-inputs", "if-quiet")
           for p in ("uniform", "first", "weighted")]


@pytest.fixture(scope="module")
def step_paths(tmp_path_factory):
    return build_program(PROGRAM, tmp_path_factory.mktemp("step_paths") / "step_paths")


@pytest.mark.parametrize("supervisor", SUPERVISORS, ids=lambda path: Path(path).stem)
def test_composed_and_general_steps_agree(step_paths, supervisor, tmp_path):
    image = tmp_path / "model.svm"
    image.write_bytes(compile_inputs([supervisor]).image)
    lines = subprocess.run([str(step_paths), str(image)], check=True, capture_output=True, text=True,
                           timeout=60).stdout.splitlines()
    assert lines == ["%s same=1 hook=1 actions=1 states=1" % options for options in OPTIONS] + ["set-in-check 1"]
