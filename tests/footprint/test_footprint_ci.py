"""Footprint reports in the project's own CI (issue 25, point 6; docs/footprint.md, "The
project's own CI"): `make footprint`'s comparison of the example with the baseline kept in the
repository; and `--cycles` from an installed swarmvm, which builds the simavr board from the
package's own C source into an empty cache. The recipes for a user's CI ("In a user's CI") are
run by test_footprint_recipes.py."""

import hashlib
import json
import os
import re
import subprocess
import tomllib
from pathlib import Path

import pytest

from checkout import EXAMPLE, ROOT
from footprint_images import KILOBOT_INDIRECT
from targets.kilobot.needs import board_or_skip

INDIRECT = [arg for declaration in KILOBOT_INDIRECT for arg in ("--indirect", declaration)]


def shrink(report: dict) -> dict:
    """The report of an image 100 B and 50 cycles smaller: what a change has grown from."""
    image = report["images"][0]
    image["flash"]["total"] -= 100
    image["flash"]["application"] -= 100
    image["cycles"]["worst"] -= 50
    return report


# ---- the project's own CI: make footprint's comparison ----------------------------------------

def make_example(build: Path, *variables: str) -> subprocess.CompletedProcess:
    return subprocess.run(["make", "-s", "--no-print-directory", "-C", str(ROOT), "footprint-example",
                           "BUILD=%s" % build, *variables], capture_output=True, text=True, timeout=900)


def test_make_footprint_prints_the_delta_against_the_baseline(build, tmp_path):
    """`make footprint-example` (which `make footprint` ends with) against the repository's
    baseline made smaller: the delta is printed, and 100 B is no failure. Cycles compare only
    across one event script (issue 36): a baseline written before the JSON recorded the script's
    digest is given the digest of the script make writes (steps 40, seed 1), the one it was
    measured with; `make footprint-baseline` writes it."""
    board_or_skip()
    baseline = json.loads((ROOT / "benchmarks" / "footprint-baseline.json").read_text())
    assert [(i["target"], i["supervisor"], i["cycles"]["steps"]) for i in baseline["images"]] == [
        ("kilobot", "energy_worker", 40)]
    events = subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "40", "--seed", "1"], check=True,
                            capture_output=True, text=True).stdout.encode()
    baseline["images"][0]["cycles"].setdefault("script_sha256", hashlib.sha256(events).hexdigest())
    smaller = tmp_path / "smaller.json"
    smaller.write_text(json.dumps(shrink(baseline)))
    result = make_example(build, "FOOTPRINT_BASELINE=%s" % smaller)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Against %s: " % smaller in result.stdout
    assert "| kilobot | energy_worker | changed |" in result.stdout
    assert "+100 B, " in result.stdout and "Growth allowed: 10 % per column." in result.stdout
    assert "cycles/step" in result.stdout and ", 40 steps: mean " in result.stdout


def test_make_footprint_fails_on_a_budget(build, tmp_path):
    board_or_skip()
    budget = tmp_path / "budget.toml"
    budget.write_text("[kilobot.rows.energy_worker]\ncycles = 100\n")
    result = make_example(build, "FOOTPRINT_BUDGET=%s" % budget)
    assert result.returncode != 0
    assert re.search(r"swarmvm: footprint: kilobot/energy_worker: cycles \d+ cycles over its budget of 100 cycles",
                     result.stderr), result.stderr
    assert "footprint-example] Error 1" in result.stderr               # the command's status 1 fails make


def test_the_projects_budgets_hold_on_the_baseline():
    """The baseline in the repository is within the project's own budgets (pyproject.toml)."""
    baseline = json.loads((ROOT / "benchmarks" / "footprint-baseline.json").read_text())
    assert baseline["budget_file"] == "pyproject.toml" and baseline["violations"] == []
    budgets = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["swarmvm"]["footprint"]["kilobot"]
    rows = budgets.pop("rows")
    assert baseline["images"][0]["budget"] == {**budgets, **rows["energy_worker"]}


# ---- --cycles from the installed package ------------------------------------------------------

def test_cycles_build_the_board_from_the_package_into_an_empty_cache(build, tmp_path):
    """`swarmvm footprint --cycles` of the swarmvm on PATH (under `make wheel-check`, the wheel's
    install, away from any checkout): the board's C source comes with the package and is built
    into the user's cache on first use, once."""
    board_or_skip()
    events = tmp_path / "events.txt"
    events.write_text(subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "5", "--seed", "2"],
                                     check=True, capture_output=True, text=True).stdout)
    cache = tmp_path / "cache"
    environment = dict(os.environ, XDG_CACHE_HOME=str(cache))
    elf = build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"
    command = ["swarmvm", "footprint", str(elf), *INDIRECT, "--cycles", str(events)]
    first = subprocess.run(command, cwd=tmp_path, env=environment, capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    assert "events.txt, 5 steps: mean " in first.stdout
    (board,) = (cache / "swarmvm").glob("kilobot_board-*")
    built = board.stat().st_mtime_ns
    again = subprocess.run(command, cwd=tmp_path, env=environment, capture_output=True, text=True)
    assert again.stdout == first.stdout and board.stat().st_mtime_ns == built


def test_cycles_without_a_c_compiler_say_what_is_missing(build, tmp_path, monkeypatch):
    """No board in the cache and no C compiler to build it: the error says what to install."""
    import swarmvm.footprint.kilobot_board
    from swarmvm import api
    from swarmvm.footprint.measure import FootprintError
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setattr(swarmvm.footprint.kilobot_board.shutil, "which", lambda name: None)
    events = tmp_path / "events.txt"
    events.write_text("-\n")
    elf = build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"
    with pytest.raises(FootprintError, match=r"^--cycles: kilobot board: needs a C compiler and simavr's headers"):
        api.measure_footprint([str(elf)], indirect=list(KILOBOT_INDIRECT), cycles=str(events))
