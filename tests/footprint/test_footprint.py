"""`swarmvm footprint`: figures from linked images, checked against binutils, and its limits.

Images: the CapBot application of two supervisors (mk/capbot.mk) and the Kilobot application
of two supervisors (mk/kilobot.mk). Totals must equal what avr-size / arm-none-eabi-size say;
the tables must be the image's exact size; the VM core must be the symbols nm finds in the
runtime's own object file. Limits must fail the command with status 1 and one line."""

import json
import re
import struct
import subprocess

import pytest
from elftools.elf.elffile import ELFFile

from conformance.cases import batch, SUPERVISORS
from swarmvm.footprint import measure as footprint
from swarmvm.compiler.runtime_files import RUNTIME_C
from footprint_images import NAMES, elf, swarmvm_footprint

M4 = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-Os", "-ffunction-sections",
      "-fdata-sections"]


def corpus_path(name):
    return next(p for p in SUPERVISORS if p.endswith("/%s.yaml" % name))


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
    rows = [line for line in result.stdout.splitlines() if line.startswith(("| capbot |", "| kilobot |"))]
    assert len(rows) == 4
    data = json.loads((tmp_path / "f.json").read_text())
    assert data["violations"] == [] and len(data["images"]) == 4
    for row in data["images"]:
        measured = footprint.measure(row["elf"])
        assert row["flash"]["total"] == measured.flash.total and row["vm"] == measured.vm
    assert "source_bytes" not in data and "Source size" not in result.stdout


def test_the_runtimes_source_sizes_are_an_option(build, tmp_path):
    """The report on a user's ELF shows the user's rows only; the project's own figures (the
    runtimes' source sizes beside the seed's KPI table) come with --runtime-sizes, as
    `make footprint` asks for them."""
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), "--runtime-sizes", "--json", tmp_path / "f.json")
    assert result.returncode == 0, result.stderr
    assert "## Source size" in result.stdout and "| C++ VM (published) | 15699 |" in result.stdout
    data = json.loads((tmp_path / "f.json").read_text())
    assert "Python VM (runtime_py/swarmvm_vm.py + swarmvm_format.py + swarmvm_step_source.py)" in data["source_bytes"]


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


def image_elf(folder):
    """A small Kilobot ELF holding energy_worker's table image as an object `swarmvm_image`
    (avr-gcc alone: no kilolib, no make)."""
    image = batch(corpus_path("energy_worker")).image
    source = folder / "energy_worker.c"
    source.write_text("const unsigned char swarmvm_image[%d] __attribute__((used)) = {%s};\n"
                      "int main(void) { return swarmvm_image[0]; }\n" % (len(image), ", ".join(map(str, image))))
    path = folder / "energy_worker.elf"
    subprocess.run(["avr-gcc", "-mmcu=atmega328p", "-Os", str(source), "-o", str(path)], check=True)
    assert footprint.measure(path).flash.tables == len(image)
    return path


def patch_image_symbol(path, field, value):
    """Overwrite a field of the ELF32 entry of `swarmvm_image` (st_value, st_shndx) or of the
    section header of its section (sh_offset), in place."""
    with open(path, "rb") as handle:
        elf = ELFFile(handle)
        table = elf.get_section_by_name(".symtab")
        index, symbol = next((i, s) for i, s in enumerate(table.iter_symbols()) if s.name == "swarmvm_image")
        section = elf.get_section(symbol["st_shndx"])
        entry = table["sh_offset"] + index * table["sh_entsize"]
        header = elf["e_shoff"] + symbol["st_shndx"] * elf["e_shentsize"]
        where = {"st_value": (entry + 4, "<I"), "st_shndx": (entry + 14, "<H"), "sh_offset": (header + 16, "<I")}
        values = dict(symbol.entry, **section.header, e_shnum=elf["e_shnum"], size=path.stat().st_size)
    offset, layout = where[field]
    data = bytearray(path.read_bytes())
    struct.pack_into(layout, data, offset, value(values))
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("field, value, reason", [
    ("st_value", lambda v: v["sh_addr"] + v["sh_size"] + 16, "lies outside its section .data"),
    ("st_value", lambda v: v["sh_addr"] + v["sh_size"] - 100, "lies outside its section .data"),
    ("st_value", lambda v: v["sh_addr"] - 8, "lies outside its section .data"),
    ("st_shndx", lambda v: v["e_shnum"] + 3, "names section"),
    ("sh_offset", lambda v: v["size"] - 8, "runs past the end of the file"),
], ids=["image_past_its_section", "image_overhanging_its_section", "image_before_its_section",
        "no_such_section", "section_past_the_end_of_the_file"])
def test_an_elf_whose_symbols_or_sections_lie_outside_is_one_line(field, value, reason, tmp_path):
    """The table image's symbol past its section gave a traceback (struct.error); one overhanging
    its section, or a section whose bytes are not in the file, gave figures the file does not
    hold. Each is now one line naming the file, exit status 2."""
    path = image_elf(tmp_path)
    patch_image_symbol(path, field, value)
    result = swarmvm_footprint(path)
    assert result.returncode == 2 and result.stdout == "" and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.startswith("swarmvm: error: %s: " % path) and reason in result.stderr


def test_json_onto_a_folder_is_one_line(tmp_path):
    """`--json FOLDER` traced back (an InputError the command did not catch), after the report."""
    path = image_elf(tmp_path)
    folder = tmp_path / "report"
    folder.mkdir()
    result = swarmvm_footprint(path, "--json", folder)
    assert result.returncode == 2 and result.stdout == "" and result.stderr == (
        "swarmvm: error: %s: --json: is a folder, not a file that can be written\n" % folder)
    assert list(folder.iterdir()) == []
