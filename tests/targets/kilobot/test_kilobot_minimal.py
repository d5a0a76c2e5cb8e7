"""The generated Kilobot program builds the minimal flash profile (runtime_c/swarmvm.h's
SVM_TRUSTED_IMAGE, no violation counter, no public-first pass for a model that receives no
message, the image without its names section) with `make MINIMAL=1` when nothing asks for more,
and still runs on the real kilolib in simavr as the full VM does; `make` builds the full VM, and so do a program of one's own and STREAM=1."""

import shutil
import subprocess
from pathlib import Path

from checkout import EXAMPLE
from conformance.cases import supervisor_yaml
from targets.kilobot.needs import board, board_or_skip, kilolib_or_skip
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import generate

PROFILE = "-DSVM_TRUSTED_IMAGE=robot_image -DSVM_WITH_PUBLIC=0 -DSVM_WITH_VIOLATIONS=0"


def _make(folder: Path, *args: str) -> Path:
    subprocess.run(["make", "-s", "robot.elf", "KILOLIB=%s" % kilolib_or_skip(), *args], cwd=folder, check=True,
                   capture_output=True)
    return folder / "robot.elf"


def _text(elf: Path) -> int:
    """The bytes of code and constants of an image (avr-size's text)."""
    sizes = subprocess.run(["avr-size", str(elf)], check=True, capture_output=True, text=True).stdout
    return int(sizes.splitlines()[1].split()[0])


def _image_bytes(elf: Path) -> int:
    """The size of the compiled-in image, robot_image (avr-nm -S)."""
    symbols = subprocess.run(["avr-nm", "-S", str(elf)], check=True, capture_output=True, text=True).stdout
    return next(int(f[1], 16) for f in map(str.split, symbols.splitlines()) if f[-1] == "robot_image")


def test_the_generated_program_runs_on_the_minimal_profile_as_on_the_full_vm(tmp_path):
    board_or_skip()
    folder = tmp_path / "robot"
    compiled = compile_inputs([str(EXAMPLE)], name="robot")
    write_outputs(folder, generate(compiled, "kilobot"))
    minimal = shutil.copy(_make(folder, "MINIMAL=1"), tmp_path / "minimal.elf")
    assert PROFILE in (folder / "robot.flags").read_text()
    full = shutil.copy(_make(folder), tmp_path / "full.elf")
    assert "TRUSTED" not in (folder / "robot.flags").read_text()
    assert _text(minimal) < _text(full)
    # the profile reads no name: its image is the one without names, the full VM's has them
    nameless = compile_inputs([str(EXAMPLE)], name="robot", names=False).image
    assert (_image_bytes(minimal), _image_bytes(full)) == (len(nameless), len(compiled.image))
    assert len(nameless) < len(compiled.image)
    runs = [board.run(elf, ticks=40, read="last_step") for elf in (minimal, full)]
    for run in runs:        # started by RUN, the VM steps at every tick to the end, no image refused (red)
        assert run.end[:1] == (40,) and run.ram >= 39
    assert runs[0].leds == runs[1].leds
    # the flags a build would use (make -n still writes them): the streaming build gets the full VM, and a
    # controller that reads the violation counter keeps it
    assert "TRUSTED" not in _flags(folder, "STREAM=1", "MINIMAL=1")
    with open(folder / "robot_controller.c", "a") as controller:
        controller.write("unsigned long robot_seen(void);\nunsigned long robot_seen(void) "
                         "{ return svm_violations(svm_kilobot_vm()); }\n")
    flags = _flags(folder, "MINIMAL=1")
    assert "-DSVM_TRUSTED_IMAGE=robot_image -DSVM_WITH_PUBLIC=0" in flags and "VIOLATIONS" not in flags


def _flags(folder: Path, *args: str) -> str:
    subprocess.run(["make", "-n", "robot.elf", "KILOLIB=%s" % kilolib_or_skip(), *args], cwd=folder, check=True,
                   capture_output=True)
    return (folder / "robot.flags").read_text()


def test_a_model_that_receives_messages_keeps_the_public_first_pass(tmp_path):
    model = tmp_path / "heard.yaml"
    model.write_text(supervisor_yaml(["go", "heard"], [1, 0], [{"go", "heard"}], [[[("go", 0), ("heard", 0)]]],
                                     public=[1, 1]))
    makefile = generate(compile_inputs([str(model)], name="robot"), "kilobot")["Makefile"][0].decode()
    assert "-DSVM_TRUSTED_IMAGE=robot_image\n" in makefile and "WITH_PUBLIC" not in makefile
