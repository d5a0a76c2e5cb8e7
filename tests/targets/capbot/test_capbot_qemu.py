"""A generated CapBot project builds its bare-metal QEMU image by itself (issue 36, point 5; issue
35, point 4): gen writes qemu/ (the start-up code, linker script, CapBot API stand-ins and
bare-metal main the package ships, and a Makefile), so `make -C qemu` in a folder outside the
checkout builds <name>.elf with arm-none-eabi-gcc beside what `swarmvm footprint` reads (the
sidecar's copy and the .su files), `make -C qemu run` runs it in QEMU, and `MINIMAL=1` builds the
minimal flash profile. The README's commands are run as written; every name a user may give
builds, in both profiles, or is refused in one line."""

import json
import os
import re
import shutil
import subprocess
import tempfile

import pytest

from checkout import EXAMPLE, ROOT
from corrupted import corrupt_compiled_in_image
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.footprint import measure
from swarmvm.targets import TARGETS, generate
from target_builds import build_in_place
from targets.capbot.app_environment import environment_script

pytestmark = pytest.mark.emulator   # runs QEMU


def _tools() -> None:
    missing = [tool for tool in ("make", "arm-none-eabi-gcc", "qemu-system-arm") if shutil.which(tool) is None]
    if missing:
        pytest.skip("needs %s" % ", ".join(missing))


def project(folder, name, model=EXAMPLE):
    """The CapBot project gen writes for ``model`` under the model name ``name``, in ``folder``."""
    _tools()
    write_outputs(folder, generate(compile_inputs([str(model)], name=name), "capbot"))
    return folder


def readme_commands(folder, heading):
    """The README's commands under ``heading`` that the bare-metal build runs (the west ones need
    the nRF Connect SDK)."""
    section = (folder / "README.md").read_text().split("## %s\n" % heading, 1)[1].split("\n## ", 1)[0]
    return [line for block in re.findall(r"```sh\n(.*?)```", section, re.S) for line in block.splitlines()
            if "qemu" in line]


# A user's shell: none of the variables through which `make test` (whose child this suite may
# be) would make these commands a sub-make, printing make[1]'s directories and messages.
USER_ENV = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS", "MAKEFILES")}


def run(command, folder):
    """(exit status, stdout, stderr) of a command whose output QEMU's semihosting writes: to files,
    not pipes (qemu_harness.run says why), run as from a user's shell."""
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        status = subprocess.run(command, cwd=folder, stdout=out, stderr=err, stdin=subprocess.DEVNULL,
                                env=USER_ENV, timeout=120).returncode
        out.seek(0)
        err.seek(0)
        return status, out.read(), err.read()


def trace(folder, *options):
    """The trace `make -C qemu run` prints (and its stderr), the build made with ``options``."""
    status, stdout, stderr = run(["make", "-s", "-C", "qemu", "run", *options], folder)
    assert status == 0, stderr
    return stdout.splitlines(), stderr


@pytest.fixture(scope="module")
def worker(tmp_path_factory):
    return project(tmp_path_factory.mktemp("capbot-qemu") / "worker", "worker")


def test_the_readme_builds_and_runs_the_bare_metal_image_as_written(worker, vm):
    build, runs = readme_commands(worker, "Build"), readme_commands(worker, "Run")
    assert build == ["make -C qemu"] and runs == ["make -C qemu run"]
    status, _, stderr = run(build[0].split(), worker)
    assert status == 0, stderr
    assert (worker / "qemu" / "worker.footprint.json").read_bytes() == (worker / "worker.footprint.json").read_bytes()
    assert sorted(p.name for p in (worker / "qemu").glob("*.su")) == sorted(
        "%s.su" % stem for stem in ("startup", "app_qemu", "capbot_qemu", "worker_controller", "worker_tables",
                                    "worker_dispatch", "swarmvm", "swarmvm_logic_page"))
    status, stdout, stderr = run(runs[0].split(), worker)
    image = vm.Image.parse((worker / "worker.svm").read_bytes())
    lines = [line for line in stdout.splitlines() if not line.startswith("make: ")]     # -C's Entering, Leaving
    assert status == 0 and lines == vm.replay(vm.VM(image), environment_script(image))
    assert stderr == "logic page: blank (never written), running the compiled-in worker\n"


def test_the_build_needs_nothing_of_the_checkout(worker):
    """Every file of qemu/ is the project's own: no path into swarmvm's checkout or package."""
    for path in (worker / "qemu").iterdir():
        if path.suffix in (".c", ".h", ".ld") or path.name == "Makefile":
            text = path.read_text()
            assert str(ROOT) not in text and "firmware/" not in text, path


def test_minimal_profile_runs_the_same_trace_in_less_flash(tmp_path, vm):
    folder = project(tmp_path / "worker", "worker")
    full, _ = trace(folder)
    full_size = measure.measure(folder / "qemu" / "worker.elf")
    minimal, stderr = trace(folder, "MINIMAL=1")
    small = measure.measure(folder / "qemu" / "worker.elf")
    assert minimal == full and stderr == "minimal profile: running the compiled-in worker (no logic page)\n"
    assert small.flash.core < full_size.flash.core and small.flash.total < full_size.flash.total
    assert small.ram.core <= full_size.ram.core
    # the flags changed back: `make` builds the full VM again, not the minimal one it has
    assert trace(folder)[1].startswith("logic page: ")


def test_the_minimal_image_is_measured_with_no_declaration(tmp_path):
    """The sidecar's declarations cover the minimal build too: its stack is known, every limit of
    the CapBot's record checked and passed."""
    folder = project(tmp_path / "worker", "worker")
    status, _, stderr = run(["make", "-s", "-C", "qemu", "MINIMAL=1"], folder)
    assert status == 0, stderr
    result = subprocess.run(["swarmvm", "footprint", "qemu/worker.elf", "--json", "fp.json"], cwd=folder,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    image = json.loads((folder / "fp.json").read_text())["images"][0]
    assert "unknown" not in image["stack"] and image["stack"]["total"] > image["stack"]["step"] > 0
    assert "| stack (limit) | capbot/worker |" in result.stdout and "0 failed" in result.stdout


def test_a_corrupted_image_is_refused_by_the_validating_build(tmp_path):
    """The default build checks the compiled-in image: one edited by hand is refused (exit 1)."""
    folder = project(tmp_path / "worker", "worker")
    corrupt_compiled_in_image(folder / "src" / "worker_tables.c")
    status, stdout, stderr = run(["make", "-s", "-C", "qemu", "run"], folder)
    assert status != 0 and stdout == ""
    assert stderr.startswith("compiled-in worker: refused (swarmvm error 4)\nmake: *** [Makefile:")


# Names that a bare-metal main naming the model by macro pasting, or declaring its own
# <name>_dispatch-like helpers, could not build: the main's own former helper (traced_dispatch),
# a macro of the C library that gen takes (stdout), the files of qemu/ (startup, app), a name
# that is not ASCII (made ouvri_re), the longest allowed; and those gen refuses for every C
# target (the C library's macros and main), in one line.
AWKWARD_NAMES = ["traced", "stdout", "startup", "app", "ouvrière", "x" * 236]
REFUSED_NAMES = ["NULL", "EOF", "errno", "main"]


@pytest.mark.parametrize("name", AWKWARD_NAMES + REFUSED_NAMES, ids=lambda n: n if len(n) < 20 else "longest")
def test_every_name_builds_and_runs_in_both_profiles_or_is_refused(name, tmp_path, vm):
    _tools()
    folder = tmp_path / "p"
    result = subprocess.run(["swarmvm", "gen", str(EXAMPLE), "--target", "capbot", "-o", str(folder), "--name", name],
                            capture_output=True, text=True)
    if name in REFUSED_NAMES:
        assert result.returncode == 2 and len(result.stderr.splitlines()) == 1 and not folder.exists()
        assert result.stderr.startswith("swarmvm: error: ") and "--name" in result.stderr
        return
    assert result.returncode == 0, result.stderr
    stem = re.sub(r"[^A-Za-z0-9_]", "_", name)
    image = vm.Image.parse((folder / ("%s.svm" % stem)).read_bytes())
    expected = vm.replay(vm.VM(image), environment_script(image))
    for profile in ([], ["MINIMAL=1"]):
        build = build_in_place(TARGETS["capbot"], folder, stem, *profile)
        assert build.returncode == 0, build.stderr
        assert trace(folder, *profile)[0] == expected
