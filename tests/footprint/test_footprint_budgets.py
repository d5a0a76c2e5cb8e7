"""Budgets (docs/footprint.md, "Budgets"): written once in pyproject.toml or a --budget file, per
target and per row; the Kilobot energy_worker made larger (conftest.py) is caught by them, with
one line per row over budget and exit status 1; a bad budget file is one line, status 2.

Before budgets, `swarmvm footprint` read no pyproject.toml (the larger image passed, status 0)
and had no --budget option (a usage error, status 2)."""

import re
import tomllib
from pathlib import Path

import pytest

from footprint_images import BALLAST_RAM, elf, swarmvm_footprint
from swarmvm.footprint import measure as footprint

DOCS = Path(__file__).resolve().parents[2] / "docs" / "footprint.md"


def docs_budget() -> str:
    """The pyproject.toml example of docs/footprint.md."""
    return re.search(r"```toml\n(.*?)```", DOCS.read_text(), re.S).group(1)


def failures(result):
    return [line.removeprefix("swarmvm: footprint: ") for line in result.stderr.splitlines()]


def test_the_documented_pyproject_budget_catches_the_larger_image(build, larger, tmp_path):
    """The docs' example, as ./pyproject.toml: the corpus images pass it; the energy_worker whose
    controller grew is over its RAM budget, named in one line."""
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "robots"\n\n' + docs_budget())
    bound = tomllib.loads(docs_budget())["tool"]["swarmvm"]["footprint"]["kilobot"]["ram"]
    images = [elf(build, t, n) for t in ("capbot", "kilobot") for n in ("energy_worker", "network_worker")]
    passing = swarmvm_footprint(*images, cwd=tmp_path)
    assert passing.returncode == 0 and passing.stderr == "", passing.stderr
    assert "Budgets: 8 checks from pyproject.toml." in passing.stdout   # 3 per Kilobot row, 1 per CapBot row
    ram = footprint.measure(larger).ram.total
    assert ram == footprint.measure(images[2]).ram.total + BALLAST_RAM > bound
    failing = swarmvm_footprint(larger, images[3], cwd=tmp_path)
    assert failing.returncode == 1
    assert failures(failing) == ["kilobot/energy_worker: ram %d B over its budget of %d B (by %d B)"
                                 % (ram, bound, ram - bound)]
    assert "**Failed:**" in failing.stdout and "| kilobot | energy_worker | %d |" % footprint.measure(larger).flash.total \
        in failing.stdout


def test_a_budget_file_replaces_pyproject_and_a_row_budget_the_targets(build, larger, tmp_path):
    """--budget FILE: tables at its top. The row's bound replaces the target's for its column
    only: network_worker may have more flash, but not more RAM."""
    (tmp_path / "pyproject.toml").write_text("[tool.swarmvm.footprint.kilobot]\nflash = 1\n")
    network = footprint.measure(elf(build, "kilobot", "network_worker"))
    small = footprint.measure(elf(build, "kilobot", "energy_worker"))
    budget = tmp_path / "budget.toml"
    budget.write_text("[kilobot]\nflash = %d\nram = %d\n[kilobot.rows.network_worker]\nflash = %d\n"
                      % (small.flash.total, network.ram.total, network.flash.total))
    images = (elf(build, "kilobot", "energy_worker"), elf(build, "kilobot", "network_worker"))
    result = swarmvm_footprint(*images, "--budget", budget, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    budget.write_text("[kilobot]\nflash = %d\nram = %d\n[kilobot.rows.network_worker]\nflash = %d\n"
                      % (small.flash.total, network.ram.total - 1, network.flash.total))
    result = swarmvm_footprint(*images, "--budget", budget, cwd=tmp_path)
    assert result.returncode == 1
    assert small.ram.total < network.ram.total - 1 and small.flash.total < network.flash.total
    assert failures(result) == [
        "kilobot/network_worker: ram %d B over its budget of %d B (by 1 B)" % (network.ram.total, network.ram.total - 1)]


def test_each_row_over_budget_is_one_line_naming_every_column(build, larger, tmp_path):
    budget = tmp_path / "budget.toml"
    budget.write_text("[kilobot]\nflash = 100\nram = 100\n[capbot]\nflash = 100\n")
    result = swarmvm_footprint(larger, elf(build, "capbot", "energy_worker"), "--budget", budget)
    assert result.returncode == 1
    lines = failures(result)
    assert len(lines) == 2
    assert lines[0].startswith("capbot/energy_worker: flash ") and ";" not in lines[0]
    assert lines[1].startswith("kilobot/energy_worker: flash ") and "; ram " in lines[1]


@pytest.mark.parametrize("name, text, key, message", [
    ("budget.toml", "[kilobot\nflash = 1\n", "", "not a TOML file (Expected ']'"),
    ("budget.toml", "[z80]\nflash = 1\n", "z80", "unknown target (one of capbot, kilobot)"),
    ("budget.toml", "[kilobot]\nflsh = 1\n", "kilobot.flsh", "unknown column (one of cycles, cycles_mean, flash,"),
    ("budget.toml", "[kilobot]\nflash = -1\n", "kilobot.flash", "must be a whole number (B), at least 0, got -1"),
    ("budget.toml", "[kilobot]\nram = \"2 kB\"\n", "kilobot.ram", "must be a whole number (B), at least 0, got '2 kB'"),
    ("budget.toml", "[kilobot]\nram = true\n", "kilobot.ram", "got True"),
    ("budget.toml", "kilobot = 3\n", "kilobot", "must be a table, got int"),
    ("budget.toml", "[kilobot]\nrows = 1\n", "kilobot.rows", "must be a table, got int"),
    ("budget.toml", "[kilobot.rows.energy_worker]\nvm = 1.5\n", "kilobot.rows.energy_worker.vm", "got 1.5"),
    ("pyproject.toml", "[tool.swarmvm]\nfootprint = 1\n", "tool.swarmvm.footprint", "must be a table"),
    ("pyproject.toml", "[tool.swarmvm.footprint.kilobot]\nheap = 1\n", "tool.swarmvm.footprint.kilobot.heap",
     "unknown column"),
], ids=["not_toml", "unknown_target", "unknown_column", "negative", "text", "bool", "target_not_a_table",
        "rows_not_a_table", "float_in_a_row", "pyproject_not_a_table", "pyproject_unknown_column"])
@pytest.mark.parametrize("given", ["option", "pyproject"])
def test_a_bad_budget_file_is_one_line_naming_file_and_key(name, text, key, message, given, tmp_path):
    """Before any image is read (the ELF here does not exist): status 2, nothing on stdout."""
    if given == "pyproject" and name != "pyproject.toml":
        text = text.replace("[", "[tool.swarmvm.footprint.", 1) if text.startswith("[") else \
            "[tool.swarmvm.footprint]\n" + text
        key = "tool.swarmvm.footprint." + key if key else key
        name = "pyproject.toml"
    (tmp_path / name).write_text(text)
    args = ["missing.elf"] + (["--budget", name] if given == "option" else [])
    result = swarmvm_footprint(*args, cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == "" and result.stderr.count("\n") == 1, result.stderr
    prefix = "swarmvm: error: %s: %s" % (name, key + ": " if key else "")
    assert result.stderr.startswith(prefix) and message in result.stderr, result.stderr


def test_a_missing_budget_file_is_one_line(tmp_path):
    result = swarmvm_footprint("missing.elf", "--budget", tmp_path / "none.toml")
    assert result.returncode == 2 and result.stderr == (
        "swarmvm: error: %s: cannot read file (No such file or directory)\n" % (tmp_path / "none.toml"))
