"""Worst-case stack in the footprint report (issue 25, point 3; docs/footprint.md, "Stack"): the
bound from the .su files the generated Kilobot Makefile writes and the call graph of the
image's disassembly; an indirect call nobody declared, or no .su data, is reported unknown,
never guessed; a callback made deeper is caught by a stack budget; static RAM plus stack is
checked against the Kilobot's 2,048 B; and the deepest stack measured in simavr by stack
painting stays within the static bound. The same for the CapBot (Cortex-M4) image of mk/capbot.mk,
its indirect calls declared as mk/capbot.mk does, measured in QEMU (startup.c's stack painting)."""

import json
import re
import shutil
import subprocess
import sys

import pytest

import capbot_images
from checkout import FIRMWARE
from footprint_images import DEEPER_ARRAY, KILOBOT_INDIRECT, swarmvm_footprint

from swarmvm import api
from swarmvm.footprint.measure import Limits

sys.path.insert(0, str(FIRMWARE / "kilobot"))

from targets.kilobot.needs import board, board_or_skip  # noqa: E402

INDIRECT = [arg for declaration in KILOBOT_INDIRECT for arg in ("--indirect", declaration)]


def example(build):
    """The bundled example as its generated Makefile built it, its .su files beside it."""
    return build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"


def stack_of(elf, tmp_path, *args):
    report = tmp_path / "report.json"
    result = swarmvm_footprint(elf, "--json", report, *args, cwd=tmp_path)
    return result, json.loads(report.read_text())["images"][0]["stack"]


def test_the_example_has_a_known_bound_within_the_sram(build, tmp_path):
    result, stack = stack_of(example(build), tmp_path, *INDIRECT)
    assert result.returncode == 0, result.stderr
    assert set(stack) == {"step", "total"}
    assert 0 < stack["step"] < stack["total"] < 2048
    row = [line for line in result.stdout.splitlines() if line.startswith("| kilobot | energy_worker |")][0]
    assert row.endswith("| %d | %d |" % (stack["total"], stack["step"]))


def test_the_kilobot_records_declarations_need_no_indirect(build, tmp_path):
    """The Kilobot target's record declares what its runtime's and kilolib's indirect calls reach
    (issue 36, point 8): without --indirect the bound is the one with the documented declarations,
    and a declaration given adds to them. An undeclared indirect call is unknown: the CapBot test below."""
    result, stack = stack_of(example(build), tmp_path)
    assert result.returncode == 0, result.stderr
    assert stack == stack_of(example(build), tmp_path, *INDIRECT)[1]
    assert stack_of(example(build), tmp_path, "--indirect", "svm_step=no_such_function")[1] == stack


def test_an_image_without_stack_usage_files_is_unknown(build, tmp_path):
    shutil.copy(example(build), tmp_path / "energy_worker.elf")
    result, stack = stack_of(tmp_path / "energy_worker.elf", tmp_path, *INDIRECT)
    assert stack["unknown"]["total"] == "no -fstack-usage data (.su files) beside energy_worker.elf"
    assert result.returncode == 1                           # the Kilobot's SRAM limit cannot be checked: fails closed
    assert "stack unknown (no -fstack-usage data (.su files) beside energy_worker.elf): its limit of " in result.stderr


def test_a_deeper_callback_is_caught_by_a_stack_budget(build, deeper, tmp_path):
    _, before = stack_of(example(build), tmp_path, *INDIRECT)
    _, after = stack_of(deeper, tmp_path, *INDIRECT)
    assert after["step"] >= before["step"] + DEEPER_ARRAY
    (tmp_path / "budget.toml").write_text("[kilobot]\nstack_step = %d\n" % (before["step"] + 16))
    passing = swarmvm_footprint(example(build), "--budget", "budget.toml", *INDIRECT, cwd=tmp_path)
    assert passing.returncode == 0, passing.stderr
    failing = swarmvm_footprint(deeper, "--budget", "budget.toml", *INDIRECT, cwd=tmp_path)
    assert failing.returncode == 1
    assert failing.stderr == ("swarmvm: footprint: kilobot/energy_worker: stack_step %d B over its budget of %d B "
                              "(by %d B)\n" % (after["step"], before["step"] + 16, after["step"] - before["step"] - 16))


def test_static_ram_plus_stack_is_checked_against_the_sram(build):
    report = api.footprint_report([str(example(build))], indirect=list(KILOBOT_INDIRECT))
    assert report.failures() == []
    row = report.rows[0]
    sram = row.values["ram"] + row.values["stack"] - 1          # one byte short
    small = api.footprint_report([str(example(build))], indirect=list(KILOBOT_INDIRECT),
                                 limits=Limits().replaced("kilobot", sram=sram, min_stack=0))
    assert small.failures() == ["kilobot/energy_worker: static RAM %d B + worst-case stack %d B = %d B exceeds the "
                                "Kilobot's %d B SRAM" % (row.values["ram"], row.values["stack"],
                                                         sram + 1, sram)]


def test_a_malformed_declaration_is_bad_input(build, tmp_path):
    result = swarmvm_footprint(example(build), "--indirect", "svm_step", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr == "swarmvm: error: indirect[0]: 'svm_step' is not CALLER=TARGET[,TARGET...]\n"


def test_the_stack_measured_in_simavr_is_within_the_static_bound(build, tmp_path):
    board_or_skip()
    _, stack = stack_of(example(build), tmp_path, *INDIRECT)
    run = board.run(example(build), ticks=400, paint_stack=True)
    assert run.end[2] == "ticks"
    assert 0 < run.stack <= stack["total"]


@pytest.fixture(scope="module")
def capbot_deeper(build, tmp_path_factory):
    return capbot_images.rebuilt(build, tmp_path_factory.mktemp("capbot-deeper"), capbot_images.DEEPER)


@pytest.fixture(scope="module")
def capbot_painted(build, tmp_path_factory):
    return capbot_images.rebuilt(build, tmp_path_factory.mktemp("capbot-painted"), cflags="-DSVM_STACK_PAINT")


def test_the_capbot_example_has_a_known_bound_once_its_indirect_calls_are_declared(build, tmp_path):
    result, stack = stack_of(capbot_images.example(build), tmp_path, *capbot_images.capbot_indirect())
    assert result.returncode == 0, result.stderr
    assert set(stack) == {"step", "total"}
    assert 0 < stack["step"] < stack["total"] < 4096
    assert stack_of(capbot_images.example(build), tmp_path)[1] == stack       # mk/capbot.mk's sidecar beside it
    alone = tmp_path / "alone"                                                 # the image and its .su files only
    alone.mkdir()
    for path in capbot_images.example(build).parent.glob("energy_worker.elf*"):
        shutil.copy(path, alone)
    undeclared = stack_of(alone / "energy_worker.elf", tmp_path)[1]
    assert set(undeclared) == {"unknown"}
    assert all(why.startswith("indirect call in ") for why in undeclared["unknown"].values()), undeclared


def test_the_capbot_stack_measured_in_qemu_is_within_the_static_bound(capbot_painted, tmp_path):
    _, stack = stack_of(capbot_painted, tmp_path, *capbot_images.capbot_indirect())
    run = subprocess.run(["timeout", "60", "qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
                          "-semihosting-config", "enable=on,target=native", "-kernel", str(capbot_painted)],
                         stdin=subprocess.DEVNULL, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    used = int(re.search(r"^stack: main used (\d+) B$", run.stderr, re.M).group(1))
    assert stack["total"] // 2 < used <= stack["total"]


def test_a_deeper_capbot_callback_is_caught_by_a_stack_budget(build, capbot_deeper, tmp_path):
    indirect = capbot_images.capbot_indirect()
    _, before = stack_of(capbot_images.example(build), tmp_path, *indirect)
    _, after = stack_of(capbot_deeper, tmp_path, *indirect)
    # The array's frame is now on the deepest path (it replaced a shallower one: growth under 300 B).
    assert after["step"] > max(before["step"], capbot_images.DEEPER_ARRAY)
    assert after["total"] > max(before["total"], capbot_images.DEEPER_ARRAY)
    (tmp_path / "budget.toml").write_text("[capbot]\nstack = %d\n" % (before["total"] + 16))
    passing = swarmvm_footprint(capbot_images.example(build), "--budget", "budget.toml", *indirect, cwd=tmp_path)
    assert passing.returncode == 0, passing.stderr
    failing = swarmvm_footprint(capbot_deeper, "--budget", "budget.toml", *indirect, cwd=tmp_path)
    assert failing.returncode == 1
    assert failing.stderr == ("swarmvm: footprint: capbot/energy_worker: stack %d B over its budget of %d B "
                              "(by %d B)\n" % (after["total"], before["total"] + 16,
                                              after["total"] - before["total"] - 16))


def test_the_documented_capbot_declarations_are_the_makefiles():
    """docs/footprint.md shows the command with mk/capbot.mk's CAPBOT_INDIRECT, which the tests above run."""
    docs = re.sub(r" *\\\n\s*", " ", (FIRMWARE.parent / "docs" / "footprint.md").read_text())
    assert "swarmvm footprint build/capbot/energy_worker.elf %s\n" % " ".join(capbot_images.capbot_indirect()) in docs
