"""Cycles per step in the footprint report (issue 25, point 4; docs/footprint.md, "Cycles per
step"): a Kilobot image run with an event script in simavr gives the same counts on every run,
its checks answer from the script, the worst step is named with its inputs, a step made slower
is caught by a `cycles` budget, and the figures are compared with a baseline like the bytes.
The CapBot (Cortex-M4, QEMU) side: test_footprint_cycles_m4.py."""

import json

import pytest

from checkout import EXAMPLE
from footprint_images import KILOBOT_INDIRECT, SLOWER_LOOPS, event_script, random_event_script, swarmvm_footprint

from swarmvm import api
from targets.kilobot.needs import board_or_skip

INDIRECT = [arg for declaration in KILOBOT_INDIRECT for arg in ("--indirect", declaration)]
SUPERVISOR = EXAMPLE


@pytest.fixture(autouse=True)
def simavr_board():
    board_or_skip()


def example(build):
    return build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"


def cycles_of(elf_path, script_path, indirect=KILOBOT_INDIRECT):
    (footprint,) = api.measure_footprint([str(elf_path)], indirect=list(indirect), cycles=str(script_path))
    return footprint.cycles


def test_counts_are_the_same_on_every_run(build, tmp_path):
    events = random_event_script(tmp_path)
    first, second = cycles_of(example(build), events), cycles_of(example(build), events)
    assert len(first.per_step) == 12
    assert first.per_step == second.per_step
    assert all(count > 100 for count in first.per_step)


def test_the_checks_answer_from_the_script(build, tmp_path):
    """Nothing occurring and everything occurring are different steps; the worst is named."""
    quiet = cycles_of(example(build), event_script(tmp_path, ["-"] * 4))
    busy = cycles_of(example(build), event_script(tmp_path, ["EV_atCharger EV_notAtWork EV_lowEnergy"] * 4))
    assert quiet.per_step != busy.per_step
    assert busy.worst_inputs == ("EV_atCharger", "EV_lowEnergy", "EV_notAtWork")
    assert quiet.worst_inputs == ()


def test_the_report_has_mean_and_worst_and_names_the_worst_step(build, tmp_path):
    events = random_event_script(tmp_path)
    result = swarmvm_footprint(example(build), *INDIRECT, "--cycles", events, "--json", tmp_path / "r.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    image = json.loads((tmp_path / "r.json").read_text())["images"][0]
    cycles = image["cycles"]
    assert set(cycles) == {"script", "script_sha256", "steps", "mean", "worst", "worst_step", "worst_inputs"}
    assert cycles["steps"] == 12 and cycles["mean"] <= cycles["worst"]
    assert "| cycles/step | worst cycles/step |" in result.stdout
    rows = [line for line in events.read_text().splitlines() if not line.startswith("#")]
    named = " ".join(cycles["worst_inputs"]) or "-"
    assert rows[cycles["worst_step"] - 1] == named
    assert "worst %d at step %d" % (cycles["worst"], cycles["worst_step"]) in result.stdout


def test_a_slower_step_is_caught_by_a_cycles_budget(build, slower, tmp_path):
    events = random_event_script(tmp_path)
    normal = cycles_of(example(build), events)
    (tmp_path / "budget.toml").write_text("[kilobot]\ncycles = %d\n" % normal.worst)
    ok = swarmvm_footprint(example(build), *INDIRECT, "--cycles", events, "--budget", "budget.toml", cwd=tmp_path)
    assert ok.returncode == 0, ok.stderr
    slow = swarmvm_footprint(slower, *INDIRECT, "--cycles", events, "--budget", "budget.toml", "--format", "junit",
                             cwd=tmp_path)
    assert slow.returncode == 1
    worst = cycles_of(slower, events).worst
    assert worst > normal.worst + 3 * SLOWER_LOOPS          # a loop round takes several cycles
    message = "kilobot/energy_worker: cycles %d cycles over its budget of %d cycles (by %d cycles)" % (
        worst, normal.worst, worst - normal.worst)
    assert slow.stderr.splitlines() == ["swarmvm: footprint: " + message]
    assert 'name="cycles &lt;= %d cycles (budget)"' % normal.worst in slow.stdout


def test_a_slower_step_shows_in_the_delta(build, slower, tmp_path):
    events = random_event_script(tmp_path)
    base = swarmvm_footprint(example(build), *INDIRECT, "--cycles", events, "--json", "base.json", cwd=tmp_path)
    assert base.returncode == 0, base.stderr
    grown = swarmvm_footprint(slower, *INDIRECT, "--cycles", events, "--baseline", "base.json", "--fail-on-growth",
                              "5", cwd=tmp_path)
    assert grown.returncode == 1
    assert "grew by more than 5 %" in grown.stderr and "cycles (+" in grown.stderr, grown.stderr


def test_without_the_dispatch_declared_the_targets_record_gives_it(build, tmp_path):
    """The Kilobot target's record declares the dispatch (issue 36, point 8): no --indirect needed."""
    events = random_event_script(tmp_path)
    result = swarmvm_footprint(example(build), "--cycles", events, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert cycles_of(example(build), events, indirect=()).per_step == cycles_of(example(build), events).per_step


def test_a_script_naming_an_unknown_event_is_bad_input(build, tmp_path):
    result = swarmvm_footprint(example(build), *INDIRECT, "--cycles", event_script(tmp_path, ["EV_nowhere"]), cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("swarmvm: error: ") and "EV_nowhere" in result.stderr


def test_the_documented_commands(build, tmp_path):
    """docs/footprint.md, "Cycles per step": its two commands, on the example built by make."""
    import subprocess
    events = subprocess.run(["swarmvm", "script", str(SUPERVISOR), "--steps", "20", "--seed", "3"], check=True,
                            capture_output=True, text=True).stdout
    (tmp_path / "events.txt").write_text(events)
    result = swarmvm_footprint(example(build), "--cycles", "events.txt", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "kilobot/energy_worker: events.txt, 20 steps: mean " in result.stdout
    assert " at step 15 (inputs: EV_atWork " in result.stdout
