"""A C++ callback that throws (docs/semantics.md, "Callbacks that raise"), as a Python one that
raises: swarmvm::CallbackError names the event and the kind of callback and nests the original
(std::exception or not); a throwing check leaves the VM as it was before the step and the next
step runs as if it had never failed; a throwing action keeps its own transition."""

import subprocess
from pathlib import Path

from checkout import EXAMPLE
from conformance.cases import HOOKED
from conformance.cpp_harness import build_program
from swarmvm.compiler.pipeline import compile_inputs

PROGRAM = Path(__file__).resolve().parent / "callback_errors.cpp"


def test_throwing_callbacks_follow_the_python_policy(tmp_path):
    image, exe = tmp_path / "energy_worker.svm", tmp_path / "callback_errors"
    image.write_bytes(compile_inputs([str(EXAMPLE)]).image)
    hooked = tmp_path / "hooked.yaml"
    hooked.write_text(HOOKED)
    (tmp_path / "hooked.svm").write_bytes(compile_inputs([str(hooked)]).image)
    build_program(PROGRAM, exe)
    lines = subprocess.run([str(exe), str(image), str(tmp_path / "hooked.svm")], check=True, capture_output=True, text=True,
                           timeout=30).stdout.splitlines()
    assert lines == [
        "check event=EV_lowEnergy kind=check what=the check of EV_lowEnergy threw: sensor unplugged "
        "cause=sensor unplugged",
        "check unchanged=1",
        "check next-step-same=1",
        "action event=EV_moveToWork kind=action what=the action of EV_moveToWork threw: motor stalled "
        "cause=motor stalled",
        "action fired=EV_moveToWork kept-transition=1",
        "other event=EV_moveToWork kind=action what=the action of EV_moveToWork threw: an exception that is not "
        "a std::exception cause=?",
        "other fired=EV_moveToWork kept-transition=1",
        "bindings same=1",
        "bindings after-load-same=1",
        "bindings unbound-never-fire=1",
        "bindings copy-same=1",
        "rebind event=EV_lowEnergy kind=check what=the check of EV_lowEnergy threw: a check cannot bind a check "
        "while the VM polls its checks cause=a check cannot bind a check while the VM polls its checks",
        "rebind unchanged=1",
        "rebind next-step-same=1",
        "hook event=EV_u kind=violation hook what=the violation hook of EV_u threw: log full cause=log full",
        "hook states=0,0 violations=1 acted=0",
        "hook next-step=2 states=0,1 acted=1",
    ]
