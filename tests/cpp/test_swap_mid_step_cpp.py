"""An image loaded during a step (docs/semantics.md, "Reset and swap"), the same in C++ as in
Python: an action that loads ends the step after its own event (the other input polled for the
old image does not fire, nor is a choice made), and the next steps run on the new image from
its initial states; the violation hook may not load. The C++ program is built with
AddressSanitizer: the action that loads is one of the actions the load replaces, and it runs on
(its captures included) after loading twice."""

import subprocess
from pathlib import Path

from conformance.cases import SWAP_FIRST, SWAP_SECOND
from conformance.cpp_harness import build_program
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import python_vm

PROGRAM = Path(__file__).resolve().parent / "swap_mid_step.cpp"
SANITIZE = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g"]
STEPS = 6


def python_lines(first: bytes, second: bytes) -> list[str]:
    """The C++ program's step lines, from the Python VM run on the same script."""
    vm_module = python_vm()
    vm = vm_module.VM(first)
    loaded: list = []

    def swap(_data):
        if not loaded:
            loaded.append(vm.load(second))
            vm.load(second)

    vm.bind("x", check=lambda _data: True, action=swap)
    vm.bind("y", check=lambda _data: True)
    lines = []
    for _ in range(STEPS):
        fired = vm.step()
        lines.append("step fired=%s states=%s violations=%d" % (",".join(map(str, fired)),
                                                               ",".join(map(str, vm.states)), vm.violations))
    return lines


def test_an_action_that_loads_ends_the_step_alike_in_cpp_and_python(tmp_path):
    first_yaml, second_yaml = tmp_path / "first.yaml", tmp_path / "second.yaml"
    first_yaml.write_text(SWAP_FIRST)
    second_yaml.write_text(SWAP_SECOND)
    first, second = (compile_inputs([str(p)]).image for p in (first_yaml, second_yaml))
    (tmp_path / "first.svm").write_bytes(first)
    (tmp_path / "second.svm").write_bytes(second)
    exe = tmp_path / "swap_mid_step"
    build_program(PROGRAM, exe, *SANITIZE)
    run = subprocess.run([str(exe), str(tmp_path / "first.svm"), str(tmp_path / "second.svm")],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stderr == "", run.stderr
    lines = run.stdout.splitlines()
    # x (2 in the first image) fires and its action loads: y (3) and the choice do not follow.
    # Then the second image: x (1), y (2, no move in state 0: a violation), b (0).
    assert lines[:2] == ["step fired=2 states=0 violations=0", "step fired=1,2,0 states=1 violations=1"]
    assert lines[:STEPS] == python_lines(first, second)
    assert lines[STEPS:] == ["hook violation hook: the violation hook cannot load an image: load it after step() returns"]
