"""A generated CapBot project measured with no hand-written declaration (issue 36, point 4): its
CMakeLists.txt copies the sidecar gen writes beside the ELF its build links (build/zephyr/), and
`swarmvm footprint` reads it there, as the README's measure command runs it.

No Zephyr SDK is installed here: CMake configures the generated CMakeLists.txt against a stand-in
Zephyr package (what it needs of Zephyr's: the ``app`` target, CONFIG_KERNEL_BIN_NAME), which is
all the copy depends on; the ELF put at build/zephyr/zephyr.elf is the generated sources linked
bare-metal for QEMU's Cortex-M4 (firmware/capbot/, as mk/capbot.mk links them), whose indirect
calls the CapBot record declares."""

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
    missing = [tool for tool in ("cmake", "arm-none-eabi-gcc", "arm-none-eabi-objdump")
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
    beside = folder / "build" / "zephyr"
    assert (beside / "zephyr.footprint.json").read_bytes() == (folder / "worker.footprint.json").read_bytes()

    flags = re.findall(r"-DSVM_(?:MAX|WITH)_[A-Z_]*=[0-9]+", (folder / "CMakeLists.txt").read_text())
    sources = [str(p) for p in sorted((folder / "src").glob("*.c")) if p.name != "main.c"]
    subprocess.run(["arm-none-eabi-gcc", "@%s" % (CAPBOT / "m4.flags"), *flags, "-DSVM_APP=worker",
                    '-DSVM_APP_HEADER="worker_tables.h"', "-I%s" % (folder / "src"), "-I%s" % CAPBOT,
                    "-T", str(CAPBOT / "mps2_an386.ld"),
                    *(str(CAPBOT / n) for n in ("startup.c", "app_qemu.c", "capbot_qemu.c")), *sources,
                    "-o", str(beside / "zephyr.elf")], cwd=folder, check=True, capture_output=True)

    readme = (folder / "README.md").read_text()
    measure = readme.split("## Measure\n", 1)[1]
    command = re.search(r"```sh\n(.*?)\n```", measure, re.S).group(1)
    assert command == "swarmvm footprint build/zephyr/zephyr.elf"
    result = subprocess.run([*command.split(), "--json", str(tmp_path / "fp.json")], cwd=folder,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    image = json.loads((tmp_path / "fp.json").read_text())["images"][0]
    assert image["target"] == "capbot" and "unknown" not in image["stack"]
    assert image["stack"]["step"] > 0 and image["stack"]["total"] > image["stack"]["step"]
    assert image["indirect"]["svm_put_decimal"] == ["to_stdout", "to_stderr"]


def test_the_sidecar_script_fits_the_bare_metal_run():
    """The bare-metal application steps the VM 20 times (firmware/capbot/app_qemu.c): a longer
    script would end before its last step, so the sidecar's has 20."""
    files = generate(compile_inputs([str(EXAMPLE)], name="worker"), "capbot")
    script = json.loads(files["worker.footprint.json"][0])["script"]
    steps = re.search(r"#define SVM_APP_STEPS (\d+)", (CAPBOT / "app_qemu.c").read_text()).group(1)
    assert len([line for line in script if not line.startswith("#")]) == int(steps)

