"""Cycles per step on the Cortex-M4 (issue 25, point 4; docs/footprint.md, "Cycles per step"):
the CapBot image of mk/capbot.mk, unchanged, run in QEMU with an event script through its GDB
stub gives the same instruction counts on every run, its checks answer from the script, the
worst step is named with its inputs, a step made slower is caught by a `cycles` budget, and a
script longer than the program's run is refused in one line."""

import json
import subprocess

import pytest

import capbot_images
from checkout import EXAMPLE
from footprint_images import event_script, random_event_script, swarmvm_footprint

from swarmvm import api

(DISPATCH,) = [declaration for declaration in capbot_images.capbot_indirect() if declaration.startswith("svm_step=")]


@pytest.fixture(scope="module")
def slower(build, tmp_path_factory):
    return capbot_images.rebuilt(build, tmp_path_factory.mktemp("capbot-slower"), capbot_images.SLOWER)


def cycles_of(elf_path, script_path):
    (footprint,) = api.measure_footprint([str(elf_path)], indirect=[DISPATCH], cycles=str(script_path))
    return footprint.cycles


def test_counts_are_the_same_on_every_run(build, tmp_path):
    events = random_event_script(tmp_path)
    first, second = cycles_of(capbot_images.example(build), events), cycles_of(capbot_images.example(build), events)
    assert len(first.per_step) == 12
    assert first.per_step == second.per_step
    assert all(count > 100 for count in first.per_step)


def test_the_checks_answer_from_the_script(build, tmp_path):
    quiet = cycles_of(capbot_images.example(build), event_script(tmp_path, ["-"] * 4))
    busy = cycles_of(capbot_images.example(build), event_script(tmp_path, ["EV_atCharger EV_notAtWork EV_lowEnergy"] * 4))
    assert quiet.per_step != busy.per_step
    assert busy.worst_inputs == ("EV_atCharger", "EV_lowEnergy", "EV_notAtWork")
    assert quiet.worst_inputs == ()


def test_a_slower_step_is_caught_by_a_cycles_budget(build, slower, tmp_path):
    events = random_event_script(tmp_path)
    normal = cycles_of(capbot_images.example(build), events)
    (tmp_path / "budget.toml").write_text("[capbot]\ncycles = %d\n" % normal.worst)
    ok = swarmvm_footprint(capbot_images.example(build), "--indirect", DISPATCH, "--cycles", events, "--budget", "budget.toml",
                           cwd=tmp_path)
    assert ok.returncode == 0, ok.stderr
    slow = swarmvm_footprint(slower, "--indirect", DISPATCH, "--cycles", events, "--budget", "budget.toml", cwd=tmp_path)
    assert slow.returncode == 1
    worst = cycles_of(slower, events).worst
    assert worst > normal.worst + 3 * capbot_images.SLOWER_LOOPS      # a loop round is several instructions
    assert slow.stderr.splitlines() == ["swarmvm: footprint: capbot/energy_worker: cycles %d cycles over its budget "
                                        "of %d cycles (by %d cycles)" % (worst, normal.worst, worst - normal.worst)]


def test_a_script_longer_than_the_run_is_refused(build, tmp_path):
    """The bare-metal application steps the VM 20 times (app_qemu.c, SVM_APP_STEPS), then exits."""
    result = swarmvm_footprint(capbot_images.example(build), "--indirect", DISPATCH, "--cycles", event_script(tmp_path, ["-"] * 21),
                               cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.endswith("energy_worker.elf: 20 of the script's 21 steps ran before the program ended "
                                  "(exit status 0)\n")
    assert len(result.stderr.splitlines()) == 1


def test_the_documented_command(build, tmp_path):
    """docs/footprint.md, "Cycles per step": the CapBot command, on the example built by make."""
    events = subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "20", "--seed", "3"], check=True,
                            capture_output=True, text=True).stdout
    (tmp_path / "events.txt").write_text(events)
    result = swarmvm_footprint(capbot_images.example(build), "--cycles", "events.txt", "--json", "report.json",
                               cwd=tmp_path)        # the dispatch declared by the sidecar mk/capbot.mk put beside it
    assert result.returncode == 0, result.stderr
    cycles = json.loads((tmp_path / "report.json").read_text())["images"][0]["cycles"]
    assert "capbot/energy_worker: events.txt, 20 steps: mean %d, worst %d at step %d" % (
        cycles["mean"], cycles["worst"], cycles["worst_step"]) in result.stdout
