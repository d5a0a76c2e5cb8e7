"""A generated CapBot project measured with no hand-written declaration (issue 36, point 4): its
CMakeLists.txt copies the sidecar gen writes beside the ELF its build links (build/zephyr/), and
`swarmvm footprint` reads it there, as the README's measure command runs it.

No Zephyr SDK is installed here: CMake configures the generated CMakeLists.txt against a stand-in
Zephyr package (what it needs of Zephyr's: the ``app`` target, CONFIG_KERNEL_BIN_NAME), which is
all the copy depends on; the ELF put at build/zephyr/zephyr.elf (with its .su files) is the
generated sources linked bare-metal for QEMU's Cortex-M4 by the project's own qemu/Makefile,
whose indirect calls the CapBot record declares. The bare-metal build is measured where it is
built too, as the README shows it: beside the sidecar's copy that build leaves."""

import json
import re
import shutil
import subprocess

import pytest

from checkout import EXAMPLE, FIRMWARE
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import generate

# What the generated CMakeLists.txt takes from Zephyr's CMake package, and nothing more.
ZEPHYR_STAND_IN = "set(CONFIG_KERNEL_BIN_NAME zephyr)\nproject(zephyr_stand_in C)\nadd_library(app STATIC)\n"
CAPBOT = FIRMWARE / "capbot"


def _tools() -> None:
    missing = [tool for tool in ("cmake", "arm-none-eabi-gcc", "arm-none-eabi-objdump", "qemu-system-arm")
               if shutil.which(tool) is None]
    if missing:
        pytest.skip("needs %s" % ", ".join(missing))


def test_the_build_leaves_the_sidecar_beside_the_elf_and_footprint_reads_it(tmp_path):
    _tools()
    folder = tmp_path / "worker"
    write_outputs(folder, generate(compile_inputs([str(EXAMPLE)], name="worker"), "capbot"))
    zephyr = tmp_path / "zephyr"
    zephyr.mkdir()
    (zephyr / "ZephyrConfig.cmake").write_text(ZEPHYR_STAND_IN)
    subprocess.run(["cmake", "-S", ".", "-B", "build", "-DZephyr_DIR=%s" % zephyr], cwd=folder, check=True,
                   capture_output=True)
    both = subprocess.run(["cmake", "-S", ".", "-B", "both", "-DZephyr_DIR=%s" % zephyr, "-DSVM_MINIMAL=ON",
                           "-DSVM_LEARNED=ON"], cwd=folder, capture_output=True, text=True)
    assert both.returncode != 0 and "SVM_MINIMAL and SVM_LEARNED: the minimal profile is built without" in both.stderr
    minimal = subprocess.run(["cmake", "-S", ".", "-B", "minimal", "-DZephyr_DIR=%s" % zephyr, "-DSVM_MINIMAL=ON"],
                             cwd=folder, capture_output=True, text=True)
    assert minimal.returncode == 0, minimal.stderr
    beside = folder / "build" / "zephyr"
    assert (beside / "zephyr.footprint.json").read_bytes() == (folder / "worker.footprint.json").read_bytes()

    subprocess.run(["make", "-s", "-C", "qemu"], cwd=folder, check=True, capture_output=True)
    shutil.copy(folder / "qemu" / "worker.elf", beside / "zephyr.elf")
    for su in (folder / "qemu").glob("*.su"):
        shutil.copy(su, beside)

    readme = (folder / "README.md").read_text()
    measure = readme.split("## Measure\n", 1)[1]
    zephyr, bare_metal = re.findall(r"```sh\n(.*?)\n```", measure, re.S)
    assert zephyr == "swarmvm footprint build/zephyr/zephyr.elf"
    assert bare_metal == ("swarmvm footprint qemu/worker.elf\n"
                          "swarmvm footprint qemu/worker.elf --cycles qemu/worker.footprint.json")
    for command in (zephyr, *bare_metal.splitlines()):
        result = subprocess.run([*command.split(), "--json", str(tmp_path / "fp.json")], cwd=folder,
                                capture_output=True, text=True)
        assert result.returncode == 0, (command, result.stderr)
        image = json.loads((tmp_path / "fp.json").read_text())["images"][0]
        assert image["target"] == "capbot" and "unknown" not in image["stack"]
        assert image["stack"]["step"] > 0 and image["stack"]["total"] > image["stack"]["step"]
        assert image["indirect"]["svm_put_decimal"] == ["to_stdout", "to_stderr"]
        assert ("cycles" in image) == ("--cycles" in command)
    assert image["cycles"]["steps"] == 20 and image["cycles"]["worst"] >= image["cycles"]["mean"] > 0


def test_the_sidecar_script_fits_the_bare_metal_run():
    """The bare-metal application steps the VM 20 times (firmware/capbot/app_qemu.c): a longer
    script would end before its last step, so the sidecar's has 20."""
    files = generate(compile_inputs([str(EXAMPLE)], name="worker"), "capbot")
    script = json.loads(files["worker.footprint.json"][0])["script"]
    steps = re.search(r"#define SVM_APP_STEPS (\d+)", (CAPBOT / "app_qemu.c").read_text()).group(1)
    assert len([line for line in script if not line.startswith("#")]) == int(steps)

