"""The C runtime, compatibility layer, harness and generated C/Kilobot sources compile without a
single warning under -std=c99 -Wall -Wextra -Wconversion -Werror -pedantic on the four compilers the project
targets: host gcc, clang, avr-gcc (ATmega328P at -Os, -O3 and the official Kilobot flags, each
image-source mode) and arm-none-eabi-gcc (Cortex-M4F, hard float)."""

import os
import shutil
import subprocess

import pytest

from conformance import c_harness
from conformance.cases import SUPERVISORS, batch
from targets.kilobot.needs import kilolib_or_skip
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_C
from checkout import FIRMWARE
from swarmvm.targets import generate

STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wconversion", "-Werror", "-pedantic"]
AVR = ["-mmcu=atmega328p"]
KILOBOT = c_harness.KILOBOT_FLAGS
ARM = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16"]
CORE = [RUNTIME_C / "swarmvm.c", RUNTIME_C / "swarmvm_sct.c", RUNTIME_C / "swarmvm_store.c",
        RUNTIME_C / "swarmvm_learn.c", RUNTIME_C / "swarmvm_learn_store.c"]
EXAMPLE = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))

COMPILERS = {
    "gcc": ["gcc", "-O2"],
    "clang": ["clang", "-O2"],
    "avr-gcc-Os": ["avr-gcc", *AVR, "-Os"],
    "avr-gcc-O3": ["avr-gcc", *AVR, "-O3"],
    "avr-gcc-kilobot": ["avr-gcc", *KILOBOT],
    "avr-gcc-kilobot-flash-only": ["avr-gcc", *KILOBOT, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"],
    "avr-gcc-kilobot-learned": ["avr-gcc", *KILOBOT, "-DSVM_LEARNED=1", "-DSVM_KILOBOT_THETA=32"],
    "avr-gcc-kilobot-ram-only": ["avr-gcc", *KILOBOT, "-DSVM_IMAGE_SOURCES=SVM_RAM_ONLY"],
    "avr-gcc-kilobot-any-source": ["avr-gcc", *KILOBOT, "-DSVM_IMAGE_SOURCES=SVM_ANY_SOURCE", "-DSVM_HARNESS_EEPROM",
                                   "-DSVM_HARNESS_CYCLES"],
    "arm-none-eabi-gcc": ["arm-none-eabi-gcc", *ARM, "-O2"],
    "arm-none-eabi-gcc-exact-Os": ["arm-none-eabi-gcc", *ARM, "-Os", "-DSVM_MASK_EXACT=1"],
    "gcc-exact-O3": ["gcc", "-O3", "-DSVM_MASK_EXACT=1"],
}


def compile_only(command, sources, includes, tmp_path):
    """Compile each source to an object; returns the compiler's complaints (empty = clean)."""
    complaints = []
    for source in sources:
        proc = subprocess.run([*command, *STRICT, *(f"-I{i}" for i in includes), "-c", str(source),
                               "-o", str(tmp_path / (source.name + ".o"))], capture_output=True, text=True)
        if proc.returncode != 0 or proc.stderr.strip():
            complaints.append("%s: %s" % (source.name, proc.stderr.strip() or "exit %d" % proc.returncode))
    return complaints


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """The example generated for the c and kilobot targets, plus a conformance header."""
    root = tmp_path_factory.mktemp("gen")
    compiled = compile_inputs([EXAMPLE], name="energy_worker")
    for target in ("c", "kilobot"):
        for rel, (data, _keep) in generate(compiled, target).items():
            (root / target / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / target / rel).write_bytes(data)
    (root / "cases").mkdir()
    (root / "cases" / "svm_cases.h").write_text(c_harness.cases_header(batch(EXAMPLE)))
    return root


@pytest.mark.parametrize("name", sorted(COMPILERS))
def test_runtime_compiles_without_warning(name, generated, tmp_path):
    command = COMPILERS[name] + c_harness.limits(batch(EXAMPLE))
    harness = FIRMWARE / "harness"
    sources = CORE + [harness / "svm_harness.c"]
    includes = [RUNTIME_C, harness, generated / "cases"]
    if command[0] == "avr-gcc":
        sources.append(harness / "platform_avr.c")
        app = generated / "kilobot"
        sources += [app / "energy_worker_app.c", app / "energy_worker_controller.c", app / "energy_worker_tables.c",
                    app / "swarmvm_kilobot.c"]
        includes += [app, kilolib_or_skip()]
    else:
        app = generated / "c"
        sources += [app / "energy_worker_main.c", app / "energy_worker_controller.c", app / "energy_worker_tables.c"]
        includes.append(app)
        if command[0] != "arm-none-eabi-gcc":
            sources.append(harness / "platform_host.c")
    assert compile_only(command, sources, includes, tmp_path) == []


def test_a_warning_is_reported(tmp_path):
    """The check itself can fail: a source with an unused variable is refused."""
    bad = tmp_path / "bad.c"
    bad.write_text("int f(void);\nint f(void) { int unused; return 0; }\n")
    assert compile_only(COMPILERS["gcc"], [bad], [], tmp_path) != []


def test_cppcheck_finds_nothing_in_the_runtime_and_the_generated_c(generated):
    """cppcheck's warning and portability checks over every runtime_c source and the example's
    generated C target, every #if configuration (--force: the runtime's feature switches make more
    than cppcheck's default 12); false positives are suppressed inline, each with its reason."""
    if shutil.which("cppcheck") is None:
        if os.environ.get("CI") == "true":
            pytest.fail("cppcheck is not installed (scripts/setup.sh installs it)")
        pytest.skip("cppcheck is not installed (apt install cppcheck)")
    sources = sorted(RUNTIME_C.glob("*.c")) + sorted((generated / "c").glob("*.c"))
    proc = subprocess.run(["cppcheck", "--quiet", "--enable=warning,portability", "--std=c99", "--inline-suppr", "--force",
                           "--error-exitcode=1", "-I", str(RUNTIME_C), *map(str, sources)],
                          capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stderr.strip() == "", proc.stderr
