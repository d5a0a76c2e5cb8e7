"""The footprint gate fails closed (issue 36; docs/footprint.md, "Limits and budgets", "Deltas
against a baseline"): a figure a budget or limit covers that is unknown fails that check, saying
why, unless the budget lets it be unknown, which the report shows; a figure that became unknown or
is no longer measured is a change the delta gate fails on; a renamed ELF is still compared (by its
table image's digest) or flagged; a baseline of another target is refused; cycles are compared
with the same event script only; a changed budget is shown; a generated Kilobot project needs no
--indirect. Each test failed on the code before: the unknown stack passed ("Budgets: 0 checks",
exit 0), 145 -> unknown was "unchanged", a renamed ELF was "new" and "removed" and passed, a
CapBot baseline passed against a Kilobot image, the JSON held no script digest and no budget was
read from a baseline, and --cycles without --indirect failed."""

import hashlib
import json
import shutil
import xml.etree.ElementTree as ET

from checkout import EXAMPLE
from footprint_images import BALLAST_FLASH, elf, event_script, random_event_script, swarmvm_footprint
from swarmvm import api
from swarmvm.footprint.measure import table_image
from targets.kilobot.needs import board, board_or_skip


def example(build):
    return elf(build, "kilobot", "energy_worker")


def report_json(tmp_path, *args, name="report.json"):
    """The JSON report of ``swarmvm footprint ARGS --json``, and the run."""
    path = tmp_path / name
    result = swarmvm_footprint(*args, "--json", path, cwd=tmp_path)
    return result, json.loads(path.read_text())


def errors(result):
    return [line.removeprefix("swarmvm: footprint: ") for line in result.stderr.splitlines()]


# 1. Unknown never passes --------------------------------------------------------------------

def test_float_arithmetic_has_a_stack_bound(build, floating, tmp_path):
    """avr-libc's __addsf3 has no size and __addsf3x jumps into its code: that code is read as a
    function of its own (``__addsf3+0x..``), so the bound is known, deeper than the example's,
    and stack painting in simavr stays within it. Before: unknown (``__addsf3x calls 0x..., in no
    sized function``)."""
    (plain,) = api.measure_footprint([str(example(build))])
    (footprint,) = api.measure_footprint([str(floating)])
    assert footprint.stack is not None and footprint.stack.unknown == {}, footprint.stack
    assert plain.stack is not None and footprint.stack.step > plain.stack.step
    board_or_skip()
    run = board.run(floating, ticks=400, paint_stack=True)
    assert run.end[2] == "ticks" and 0 < run.stack <= footprint.stack.total


def test_an_unknown_stack_fails_its_budget_and_the_sram_limit(estimating, tmp_path):
    """kilolib's estimate_distance() (built without .su files) moves the stack pointer: the stack
    is unknown, and the stack budget and the Kilobot's SRAM limit fail, one line naming why, each
    a failed JUnit test case. Before: "Budgets: 0 checks", no test case, status 0."""
    (tmp_path / "budget.toml").write_text("[kilobot]\nstack = 150\n")
    result = swarmvm_footprint(estimating, "--budget", "budget.toml", cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    (line,) = errors(result)
    assert line.startswith("kilobot/energy_worker: stack unknown (no stack usage data for estimate_distance ")
    assert "declare its frame with --frame estimate_distance=BYTES" in line
    assert "its limit of " in line and "its budget of 150 B cannot be checked" in line
    assert "Budgets: 1 checks from budget.toml." in result.stdout
    junit = swarmvm_footprint(estimating, "--budget", "budget.toml", "--format", "junit", cwd=tmp_path)
    assert junit.returncode == 1
    failed = {case.get("name"): case.find("failure").get("message")
              for case in ET.fromstring(junit.stdout).iter("testcase") if case.find("failure") is not None}
    ram = api.measure_footprint([str(estimating)])[0].ram.total
    assert set(failed) == {"stack <= 150 B (budget)", "stack <= %d B (limit)" % (2048 - ram)}, failed
    assert all(message.startswith("stack unknown (") for message in failed.values())


def test_allow_unknown_is_an_explicit_opt_out_shown_in_the_report(estimating, tmp_path):
    (tmp_path / "budget.toml").write_text('[kilobot]\nstack = 150\n[kilobot.rows.energy_worker]\n'
                                          'allow_unknown = ["stack"]\n')
    result = swarmvm_footprint(estimating, "--budget", "budget.toml", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Not checked:" in result.stdout
    assert "allowed by kilobot.rows.energy_worker.allow_unknown" in result.stdout
    junit = swarmvm_footprint(estimating, "--budget", "budget.toml", "--format", "junit", cwd=tmp_path)
    root = ET.fromstring(junit.stdout)
    assert root.find("testsuite").get("skipped") == "2" and root.find("testsuite").get("failures") == "0"


def test_allow_unknown_names_columns(tmp_path):
    (tmp_path / "budget.toml").write_text('[kilobot]\nallow_unknown = ["stak"]\n')
    result = swarmvm_footprint("missing.elf", "--budget", "budget.toml", cwd=tmp_path)
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    assert result.stderr.startswith("swarmvm: error: budget.toml: kilobot.allow_unknown: unknown column 'stak'")


def test_a_cycles_budget_without_cycles_is_shown_not_checked(build, tmp_path):
    (tmp_path / "budget.toml").write_text("[kilobot]\ncycles = 4000\n")
    result = swarmvm_footprint(example(build), "--budget", "budget.toml", "--format", "junit", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    (case,) = [c for c in ET.fromstring(result.stdout).iter("testcase") if c.get("name").startswith("cycles")]
    assert case.find("skipped").get("message") == (
        "cycles not measured, its budget of 4000 cycles not checked (give --cycles SCRIPT)")


# 2. Known -> unknown, measured -> not measured, is a change -----------------------------------

def test_a_stack_that_became_unknown_is_a_change_the_gate_fails(build, estimating, tmp_path):
    _, data = report_json(tmp_path, example(build), name="main.json")
    was = data["images"][0]["stack"]["total"]
    (tmp_path / "budget.toml").write_text('[kilobot]\nallow_unknown = ["stack", "stack_step"]\n')
    result = swarmvm_footprint(estimating, "--baseline", "main.json", "--fail-on-growth", "1000", "--budget",
                               "budget.toml", cwd=tmp_path)
    assert result.returncode == 1
    row = [line for line in result.stdout.splitlines() if line.startswith("| kilobot | energy_worker | changed |")]
    assert row and "unknown (was %d B)" % was in row[0], result.stdout
    assert "cannot be judged: stack (was %d B, now unknown: no stack usage data for estimate_distance" % was \
        in result.stderr


def test_cycles_no_longer_measured_is_a_change_the_gate_fails(build, tmp_path):
    _, data = report_json(tmp_path, example(build), name="main.json")
    data["images"][0]["cycles"] = dict(script="events.txt", script_sha256="0" * 64, steps=12, mean=2000, worst=3000,
                                       worst_step=1, worst_inputs=[])
    (tmp_path / "main.json").write_text(json.dumps(data))
    result = swarmvm_footprint(example(build), "--baseline", "main.json", "--fail-on-growth", "10", cwd=tmp_path)
    assert result.returncode == 1
    assert "| changed |" in result.stdout and "| not measured (was 3000 cycles) |" in result.stdout, result.stdout
    assert "cycles (was 3000 cycles, now not measured: no longer measured)" in result.stderr


# 3. A renamed ELF ----------------------------------------------------------------------------

def renamed(image, folder, name="robot"):
    """``image``'s folder copied to ``folder`` with the ELF renamed (its .su files beside it)."""
    shutil.copytree(image.parent, folder)
    (folder / image.name).rename(folder / ("%s.elf" % name))
    return folder / ("%s.elf" % name)


def test_a_renamed_elf_is_matched_by_its_table_image_and_its_growth_caught(build, larger, tmp_path):
    report_json(tmp_path, example(build), name="main.json")
    robot = renamed(larger, tmp_path / "pr")
    result = swarmvm_footprint(robot, "--baseline", "main.json", "--fail-on-growth", "5", cwd=tmp_path)
    assert result.returncode == 1
    assert "| kilobot | robot (was energy_worker) | renamed |" in result.stdout
    assert "kilobot/robot: grew by more than 5 %: flash (+" in result.stderr
    assert BALLAST_FLASH > 0


def test_a_rename_the_digests_do_not_confirm_fails_the_gate(build, tmp_path):
    report_json(tmp_path, elf(build, "kilobot", "network_worker"), name="main.json")
    robot = renamed(example(build), tmp_path / "pr")
    result = swarmvm_footprint(robot, "--baseline", "main.json", "--fail-on-growth", "5", cwd=tmp_path)
    assert result.returncode == 1
    assert errors(result) == ["kilobot/robot: new, while kilobot/network_worker is removed: an image renamed? its "
                              "growth cannot be judged (name the ELF as in the baseline, or write the baseline again)",
                              "main.json: nothing compared: no row of the report is in the baseline (write the "
                              "baseline again)"]


def test_a_row_budget_naming_no_image_is_an_error(build, tmp_path):
    robot = renamed(example(build), tmp_path / "pr")
    (tmp_path / "budget.toml").write_text("[kilobot.rows.energy_worker]\nflash = 100\n")
    result = swarmvm_footprint(robot, "--budget", "budget.toml", cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == ("swarmvm: error: budget.toml: kilobot.rows.energy_worker: no kilobot image named "
                             "energy_worker among those measured (robot): rename the table or the ELF\n")


# 4. A baseline of another target ---------------------------------------------------------------

def test_a_baseline_of_another_target_is_refused(build, tmp_path):
    report_json(tmp_path, elf(build, "capbot", "energy_worker"), name="capbot.json")
    result = swarmvm_footprint(example(build), "--baseline", "capbot.json", cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == ("swarmvm: error: capbot.json: images: a baseline of capbot images, the report's are "
                             "kilobot: the targets differ, nothing can be compared (use a baseline of the same "
                             "target)\n")


def test_nothing_compared_fails_the_gate(build, tmp_path):
    _, data = report_json(tmp_path, example(build), name="main.json")
    data["images"] = []
    (tmp_path / "main.json").write_text(json.dumps(data))
    result = swarmvm_footprint(example(build), "--baseline", "main.json", "--fail-on-growth", "5", cwd=tmp_path)
    assert result.returncode == 1
    assert errors(result) == ["main.json: nothing compared: no row of the report is in the baseline (write the "
                              "baseline again)"]


# 5. Cycles of one event script only -------------------------------------------------------------

def test_cycles_of_another_event_script_are_not_compared(build, tmp_path):
    board_or_skip()
    first = random_event_script(tmp_path, seed=3)
    _, data = report_json(tmp_path, example(build), "--cycles", first, name="main.json")
    cycles = data["images"][0]["cycles"]
    assert len(cycles["script_sha256"]) == 64 and cycles["steps"] == 12
    other = event_script(tmp_path, ["-"] * 12)                 # the same length, other steps
    result = swarmvm_footprint(example(build), "--cycles", other, "--baseline", "main.json", "--fail-on-growth",
                               "1000", cwd=tmp_path)
    assert result.returncode == 1
    assert "(another event script)" in result.stdout
    assert "cycles_mean (" in result.stderr and "measured with another event script (sha256 " in result.stderr
    same = swarmvm_footprint(example(build), "--cycles", first, "--baseline", "main.json", "--fail-on-growth", "0",
                             cwd=tmp_path)
    assert same.returncode == 0, same.stderr


# 6. Budgets recorded, a changed one shown --------------------------------------------------------

def test_a_loosened_budget_is_shown_before_and_after(build, tmp_path):
    (tmp_path / "budget.toml").write_text("[kilobot]\nram = 300\n")
    _, data = report_json(tmp_path, example(build), "--budget", "budget.toml", name="main.json")
    assert data["images"][0]["budget"] == {"ram": 300}
    (tmp_path / "budget.toml").write_text("[kilobot]\nram = 400\nflash = 20000\n")
    result = swarmvm_footprint(example(build), "--budget", "budget.toml", "--baseline", "main.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "- kilobot/energy_worker: flash from none to 20000 B (added), ram from 300 to 400 B (loosened)" in result.stdout
    assert "| kilobot | energy_worker | changed |" in result.stdout


# 8. No hand-written declarations for a generated Kilobot project ---------------------------------

def test_a_generated_kilobot_project_needs_no_indirect(build, tmp_path):
    """The Kilobot target's record declares what its runtime's and kilolib's indirect calls
    reach: the stack is known and --cycles runs, without --indirect; the JSON names them."""
    result, data = report_json(tmp_path, example(build))
    assert result.returncode == 0, result.stderr
    image = data["images"][0]
    assert set(image["stack"]) == {"step", "total"}
    assert image["indirect"]["svm_step"] == ["svm_kilobot_app_dispatch", "dispatch"]
    board_or_skip()
    cycles = swarmvm_footprint(example(build), "--cycles", random_event_script(tmp_path), cwd=tmp_path)
    assert cycles.returncode == 0, cycles.stderr
    assert "random.txt, 12 steps: mean " in cycles.stdout


def test_cycles_without_a_dispatch_says_so(build, tmp_path):
    """The CapBot target declares no dispatch (its images come from more than one build: the
    sidecar gen writes declares its project's): an image without its sidecar, the error says so,
    not "(none of no name given is in the image)"."""
    events = random_event_script(tmp_path)
    alone = tmp_path / "energy_worker.elf"                 # no energy_worker.footprint.json beside it
    shutil.copy(elf(build, "capbot", "energy_worker"), alone)
    result = swarmvm_footprint(alone, "--cycles", events, cwd=tmp_path)
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    assert "declare it with --indirect svm_step=NAME,... (target capbot declares none)" in result.stderr
    assert EXAMPLE.is_file()


# 7. What a reviewer needs (in part) -------------------------------------------------------------

def test_every_check_shows_its_figure_bound_and_margin(build, tmp_path):
    """Before: a budget and its margin showed only when exceeded."""
    (tmp_path / "budget.toml").write_text("[kilobot]\nflash = 20000\n")
    flash = api.measure_footprint([str(example(build))])[0].flash.total
    result = swarmvm_footprint(example(build), "--budget", "budget.toml", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "| flash (budget) | kilobot/energy_worker | %d B | 20000 B | %+d B (%.1f %%) | passed |" % (
        flash, 20000 - flash, 100 * (20000 - flash) / 20000) in result.stdout


def test_a_changed_figure_shows_before_and_after(build, larger, tmp_path):
    _, data = report_json(tmp_path, example(build), name="main.json")
    before = data["images"][0]["flash"]["total"]
    result = swarmvm_footprint(larger, "--baseline", "main.json", cwd=tmp_path)
    after = api.measure_footprint([str(larger)])[0].flash.total
    assert "| %d (was %d: %+d B, " % (after, before, after - before) in result.stdout


def test_the_json_says_what_the_figures_are_of(build, tmp_path):
    """The ELF's digest, the compiler its .comment names and the table image's digest."""
    _, data = report_json(tmp_path, example(build))
    image = data["images"][0]
    assert image["elf_sha256"] == hashlib.sha256(example(build).read_bytes()).hexdigest()
    assert any(text.startswith("GCC: ") for text in image["compiler"]), image["compiler"]
    assert image["tables_sha256"] == hashlib.sha256(table_image(example(build))).hexdigest()


def test_a_declared_frame_bounds_a_function_without_stack_usage_data(estimating, tmp_path):
    """The way out for a library built without -fstack-usage: --frame FUNCTION=BYTES, a
    declaration like --indirect, recorded in the JSON. estimate_distance pushes 18 registers and
    makes 6 bytes of room (three `rcall .+0`) after its 2-byte return address: 26 B. Stack
    painting in simavr stays within the bound."""
    result, data = report_json(tmp_path, estimating, "--frame", "estimate_distance=26")
    assert result.returncode == 0, result.stderr
    image = data["images"][0]
    assert set(image["stack"]) == {"step", "total"} and image["frames"] == {"estimate_distance": 26}
    bad = swarmvm_footprint(estimating, "--frame", "estimate_distance", cwd=tmp_path)
    assert bad.returncode == 2 and bad.stderr == (
        "swarmvm: error: frame[0]: 'estimate_distance' is not FUNCTION=BYTES\n")
    board_or_skip()
    run = board.run(estimating, ticks=400, paint_stack=True)
    assert run.end[2] == "ticks" and 0 < run.stack <= image["stack"]["total"]
