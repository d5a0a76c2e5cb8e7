"""`swarmvm footprint`: figures from linked images, checked against binutils, and its limits.

Images: the CapBot application of two supervisors (mk/capbot.mk) and the Kilobot application
of two supervisors (mk/kilobot.mk). Totals must equal what avr-size / arm-none-eabi-size say;
the tables must be the image's exact size; the VM core must be the symbols nm finds in the
runtime's own object file. Limits must fail the command with status 1 and one line."""

import json
import re
import subprocess

import pytest

from conformance.cases import batch, SUPERVISORS
from swarmvm import footprint
from swarmvm.runtime import RUNTIME_C
from checkout import ROOT

NAMES = ("energy_worker", "network_worker")
M4 = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-Os", "-ffunction-sections",
      "-fdata-sections"]


def corpus_path(name):
    return next(p for p in SUPERVISORS if p.endswith("/%s.yaml" % name))


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("footprint")
    targets = ["%s/%s/%s.elf" % (root, target, name) for target in ("capbot", "kilobot") for name in NAMES]
    subprocess.run(["make", "-s", "-C", str(ROOT), "BUILD=%s" % root, *targets], check=True,
                   capture_output=True, text=True)
    return root


def elf(build, target, name):
    return build / target / ("%s.elf" % name)


def swarmvm_footprint(*args):
    return subprocess.run(["swarmvm", "footprint", *map(str, args)], capture_output=True, text=True)


def avr_sizes(path):
    out = subprocess.run(["avr-size", "-A", str(path)], check=True, capture_output=True, text=True).stdout
    return {name: int(size) for name, size in re.findall(r"^(\.\w+)\s+(\d+)", out, re.M)}


def berkeley_sizes(path):
    out = subprocess.run(["arm-none-eabi-size", str(path)], check=True, capture_output=True, text=True).stdout
    text, data, bss = map(int, out.splitlines()[1].split()[:3])
    return text, data, bss


@pytest.mark.parametrize("name", NAMES)
def test_totals_agree_with_binutils(build, name):
    capbot = footprint.measure(elf(build, "capbot", name))
    text, data, bss = berkeley_sizes(elf(build, "capbot", name))
    assert (capbot.target, capbot.flash.total, capbot.ram.total) == ("capbot", text + data, data + bss)
    kilobot = footprint.measure(elf(build, "kilobot", name))
    sizes = avr_sizes(elf(build, "kilobot", name))
    assert kilobot.target == "kilobot"
    assert kilobot.flash.total == sizes[".text"] + sizes.get(".data", 0)
    assert kilobot.ram.total == sizes.get(".data", 0) + sizes.get(".bss", 0) + sizes.get(".noinit", 0)


@pytest.mark.parametrize("target", ["capbot", "kilobot"])
@pytest.mark.parametrize("name", NAMES)
def test_tables_are_the_image(build, target, name):
    measured = footprint.measure(elf(build, target, name))
    assert measured.flash.tables == len(batch(corpus_path(name)).image)
    assert measured.ram.tables == 0
    split = measured.flash
    assert split.core + split.tables + split.application == split.total and split.application > 0


def test_vm_core_is_what_nm_finds_in_the_runtime_object(build, tmp_path):
    """Independent attribution: the symbols of the runtime objects the CapBot links (swarmvm.o and
    swarmvm_logic_page.o, compiled alone, same flags), looked up by nm in the linked image, plus
    the VM instance `vm`."""
    own = set()
    for source in ("swarmvm.c", "swarmvm_logic_page.c"):
        obj = tmp_path / source.replace(".c", ".o")
        subprocess.run(["arm-none-eabi-gcc", "-std=c99", *M4, "-DSVM_MAX_EVENTS=30", "-DSVM_MAX_SUPERVISORS=8",
                        "-c", str(RUNTIME_C / source), "-o", str(obj)], check=True)
        own |= set(subprocess.run(["arm-none-eabi-nm", "--defined-only", "-j", str(obj)], check=True,
                                  capture_output=True, text=True).stdout.split())
    image = elf(build, "capbot", "network_worker")
    listed = subprocess.run(["arm-none-eabi-nm", "-S", "--defined-only", str(image)], check=True,
                            capture_output=True, text=True).stdout
    core = {}
    for line in listed.splitlines():
        parts = line.split()
        if len(parts) == 4 and (parts[3] in own or parts[3] == "vm"):
            core[parts[3]] = int(parts[1], 16)
    measured = footprint.measure(image)
    assert "svm_step" in core and "vm" in core
    assert measured.flash.core + measured.ram.core == sum(core.values())
    assert measured.ram.core == core["vm"]


def test_report_lists_every_image_and_writes_json(build, tmp_path):
    images = [elf(build, t, n) for t in ("capbot", "kilobot") for n in NAMES]
    result = swarmvm_footprint(*images, "--json", tmp_path / "f.json")
    assert result.returncode == 0, result.stderr
    rows = [line for line in result.stdout.splitlines() if line.startswith("| capbot") or line.startswith("| kilobot")]
    assert len(rows) == 4
    data = json.loads((tmp_path / "f.json").read_text())
    assert data["violations"] == [] and len(data["images"]) == 4
    for row in data["images"]:
        measured = footprint.measure(row["elf"])
        assert row["flash"]["total"] == measured.flash.total and row["vm"] == measured.vm
    assert "Python VM (runtime_py/swarmvm_vm.py + swarmvm_format.py)" in data["source_bytes"]


@pytest.mark.parametrize("option, reason", [
    (("--kilobot-flash", "1000"), "flash"),
    (("--kilobot-stack", "2000"), "stack"),
    (("--vm-limit", "1000"), "KPI"),
])
def test_limits_fail_the_command(build, option, reason):
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), *option)
    assert result.returncode == 1
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and reason in lines[0] and "kilobot/energy_worker" in lines[0]


def test_capbot_images_are_not_held_to_the_kilobot_limits(build):
    result = swarmvm_footprint(elf(build, "capbot", "energy_worker"), "--kilobot-flash", "1000", "--kilobot-stack", "2000")
    assert result.returncode == 0, result.stderr


def test_an_elf_without_an_image_is_an_input_error(tmp_path):
    source = tmp_path / "empty.c"
    source.write_text("int main(void) { return 0; }\n")
    image = tmp_path / "empty.elf"
    subprocess.run(["avr-gcc", "-mmcu=atmega328p", "-Os", str(source), "-o", str(image)], check=True)
    result = swarmvm_footprint(image)
    assert result.returncode == 2 and result.stderr == (
        "swarmvm: error: %s: no table image (magic 'SVMI') found among its symbols\n" % image)


@pytest.mark.parametrize("kind", ["missing", "folder", "not_elf", "truncated_elf"])
def test_a_file_that_is_no_elf_is_one_line_naming_it(kind, tmp_path):
    path = tmp_path / (kind + ".elf")
    if kind == "folder":
        path.mkdir()
    elif kind != "missing":
        path.write_bytes(b"int main;\n" if kind == "not_elf" else b"\x7fELF\x01")
    result = swarmvm_footprint(path)
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    assert result.stderr.startswith("swarmvm: error: %s: " % path)
