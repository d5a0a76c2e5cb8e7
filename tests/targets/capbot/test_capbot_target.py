"""The capbot target: a complete, deterministic Zephyr application, and its bare-metal build.

The nRF Connect SDK is not available here, so the Zephyr files are checked for completeness
(every source built, every include resolvable, the 100 ms step) and main.c is compiled against
declaration-only Zephyr stand-ins; the application itself (tables, dispatch, controller, VM)
is linked bare-metal for the Cortex-M4F by `make` (mk/capbot.mk) and run in QEMU, where its
trace must equal the Python reference."""

import re
import subprocess

import pytest

from conformance import qemu_harness
from targets.capbot.app_environment import environment_script
from conformance.cases import SUPERVISORS
from checkout import ROOT
from swarmvm.targets.capbot import LIMITS
from corrupted import corrupt_compiled_in_image
from target_builds import image_path, make_images

pytestmark = pytest.mark.emulator   # runs simavr or QEMU

EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
WARNINGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
EXPECTED_FILES = {"CMakeLists.txt", "prj.conf", "energy_worker.svm", "src/main.c",
                  "src/energy_worker_tables.h", "src/energy_worker_tables.c", "src/energy_worker_dispatch.c",
                  "src/energy_worker_controller.c", "src/swarmvm_format.h", "src/swarmvm_crc_tables.h",
                  "src/swarmvm.h", "src/swarmvm.c",
                  "src/swarmvm_sct.h", "src/swarmvm_sct.c", "src/swarmvm_trace.h", "src/swarmvm_logic_page.h",
                  "src/swarmvm_logic_page.c", "learned.conf", "README.md", "energy_worker.footprint.json"} | {
                  "src/swarmvm_%s.%s" % (m, x) for m in ("learn", "learn_store", "store", "store_zephyr") for x in "ch"} | {
                  "qemu/%s" % n for n in ("Makefile", "svm_app.h", "startup.c", "app_qemu.c", "capbot_qemu.c", "capbot.h",
                                          "mps2_an386.ld")}


def gen(model, outdir, name="energy_worker"):
    subprocess.run(["swarmvm", "gen", str(model), "--target", "capbot", "-o", str(outdir), "--name", name],
                   check=True, capture_output=True, text=True)
    return outdir


def tree(root):
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    return gen(EXAMPLE, tmp_path_factory.mktemp("capbot") / "energy_worker")


def test_generated_zephyr_application_is_complete(app):
    assert set(tree(app)) == EXPECTED_FILES
    cmake = (app / "CMakeLists.txt").read_text()
    assert "find_package(Zephyr REQUIRED" in cmake and "project(energy_worker)" in cmake
    for source in (app / "src").glob("*.c"):
        assert "src/%s" % source.name in cmake, "%s is not built" % source.name
    assert "-DSVM_MAX_EVENTS=10 -DSVM_MAX_SUPERVISORS=4" in cmake
    for source in (app / "src").iterdir():
        for header in re.findall(r'#include "([^"]+)"', source.read_text()):
            assert header == "capbot.h" or (app / "src" / header).exists(), "%s includes %s" % (source.name, header)
    conf = (app / "prj.conf").read_text()
    for option in ("CONFIG_GPIO=y", "CONFIG_PWM=y", "CONFIG_ADC=y", "CONFIG_ENTROPY_GENERATOR=y",
                   "CONFIG_MAIN_STACK_SIZE=%d" % LIMITS.min_stack):     # the stack the CapBot's limits keep free
        assert option in conf


def test_main_steps_the_vm_every_100_ms(app):
    main = (app / "src" / "main.c").read_text()
    for needed in ("#include <zephyr/kernel.h>", "K_MSEC(100)", "k_timer_start(&step_timer, STEP_PERIOD, STEP_PERIOD)",
                   "k_timer_status_sync(&step_timer)", "svm_step(&vm)", "energy_worker_dispatch(machine, own, op)",
                   "energy_worker_load(&vm)", "svm_logic_page_load(&vm, energy_worker_image", "cb_motor_init()"):
        assert needed in main


def test_controller_skeleton_uses_the_capbot_api(app, vm):
    controller = (app / "src" / "energy_worker_controller.c").read_text()
    image = vm.Image.parse((app / "energy_worker.svm").read_bytes())
    assert "cb_set_motor_speed(&speeds)" in controller
    for e, name in enumerate(image.names):
        assert "void energy_worker_on_%s(void)" % name in controller
        has_check = "unsigned char energy_worker_check_%s(void)" % name in controller
        assert has_check == (not image.controllable >> e & 1)


def test_generation_is_deterministic_and_path_free(tmp_path):
    first = tree(gen(EXAMPLE, tmp_path / "a"))
    second = tree(gen(EXAMPLE, tmp_path / "elsewhere" / "b"))
    assert first == second
    for name, data in first.items():
        assert str(tmp_path).encode() not in data and str(ROOT).encode() not in data, name


MINIMAL = ("-DSVM_TRUSTED_IMAGE=energy_worker_image", "-DSVM_WITH_PUBLIC=0")     # CMakeLists.txt's SVM_MINIMAL=ON


@pytest.mark.parametrize("compiler, learned", [
    pytest.param(compiler, variant, id="%s-%s" % (compiler, name))
    for compiler in ("gcc", "clang", "arm-none-eabi-gcc")
    for name, variant in (("plain", ()), ("learned", ("-DSVM_LEARNED=1", "-DSVM_MAX_STATES=16")), ("minimal", MINIMAL))])
def test_every_source_compiles_without_warning(app, compiler, learned, tmp_path):
    """All of src/ (main.c against firmware/capbot's declaration-only Zephyr and CapBot
    headers; with -DSVM_LEARNED=ON's definitions too: the store on Zephyr's flash map; with
    -DSVM_MINIMAL=ON's, all but the logic page, which that build leaves out), C99 with -Wall
    -Wextra -Werror -pedantic."""
    cmake = (app / "CMakeLists.txt").read_text()
    assert "if(SVM_MINIMAL)\n    target_compile_definitions(app PRIVATE %s)" % " ".join(f[2:] for f in MINIMAL) in cmake
    cpu = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16"] if compiler.startswith("arm") else []
    for source in sorted((app / "src").glob("*.c")):
        if learned == MINIMAL and source.name == "swarmvm_logic_page.c":
            continue
        subprocess.run([compiler, *WARNINGS, *cpu, *learned, "-DSVM_MAX_EVENTS=10", "-DSVM_MAX_SUPERVISORS=4",
                        "-I", str(qemu_harness.CAPBOT), "-I", str(app / "src"), "-c", str(source),
                        "-o", str(tmp_path / (source.stem + ".o"))], check=True)


def build_with_make(build, name):
    elf = image_path(build, "capbot", name)
    make_images(build, [elf])
    return elf


@pytest.mark.parametrize("name", ["energy_worker", "network_worker", "public_example"])
def test_bare_metal_application_runs_in_qemu_like_the_reference(name, tmp_path, vm):
    """The generated application, linked by mk/capbot.mk, prints the reference trace in QEMU."""
    elf = build_with_make(tmp_path, name)
    image = vm.Image.parse((tmp_path / "capbot" / "gen" / name / ("%s.svm" % name)).read_bytes())
    expected = vm.replay(vm.VM(image), environment_script(image))
    status, output = qemu_harness.run_qemu(elf, timeout=30)
    assert status == 0
    assert output.splitlines() == expected
    assert any("," in line.split()[1] for line in expected), "the script should make several events fire"


def test_make_builds_an_image_for_every_corpus_supervisor():
    """mk/capbot.mk has an image rule for the example and for each corpus file stem."""
    out = subprocess.run(["make", "-n", "-C", str(ROOT), "BUILD=/nonexistent"] +
                         ["/nonexistent/capbot/%s.elf" % p.rsplit("/", 1)[1][:-5] for p in SUPERVISORS],
                         check=True, capture_output=True, text=True).stdout
    assert out.count("--target capbot") == len(SUPERVISORS)


def test_a_corrupted_compiled_in_image_is_refused_in_qemu(tmp_path):
    """The application linked by mk/capbot.mk, its compiled-in image with one bit flipped: QEMU
    shows the refusal with SVM_ERR_CRC (4) and no step, exit status 1."""
    elf = build_with_make(tmp_path, "energy_worker")
    corrupt_compiled_in_image(tmp_path / "capbot" / "gen" / "energy_worker" / "src" / "energy_worker_tables.c")
    elf.unlink()
    build_with_make(tmp_path, "energy_worker")
    status, stdout, stderr = qemu_harness.run(elf, timeout=30)
    assert status == 1 and stdout == ""
    assert stderr == "compiled-in energy_worker: refused (swarmvm error 4)\n"
