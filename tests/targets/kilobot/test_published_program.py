"""A published-style Kilobot program on the published-form VM and, moved over, on swarmvm in exact
mode (issue 35, point 5, the Kilobot half; docs/robots/kilobot.md, "Moving a published program
over").

The program (published_style/program.c, written here from the issue's description: the published
one has no licence) is one kilolib file. The test puts between its two "SCT VM" markers the
published-form tables of the energy worker (tests/nadzoru_c_form.py's text, the defines above
the arrays as the inline layout has them, what benchmarks/published_form/tables.py writes) and
the published-form generic C VM (benchmarks/published_form/published_vm.c), in place of the
VM's `#include SCT_TABLES`: the one file a user has.

  (a) that file, built with avr-gcc and kilolib as the generated Makefile builds a program
      (its CFLAGS and LDFLAGS), -DSCT_RANDOM=rand_soft as the published program draws;
  (b) the same file moved over by the doc's steps, every command of its ```sh blocks run:
      `swarmvm gen program.c` (the tables read from the program itself) with --sct-header,
      the VM section replaced by the header's #include, the states read with SCT_state(i),
      then the generated Makefile with MAIN="program.c swarmvm_sct.c" and SVM_SCT_EXACT=1.

Both run in simavr on the real kilolib (firmware/kilobot/board.py) with the same kilo_uid, the
same IR messages (neighbours' types 119 and 120, an ARK configuration, type 10, for another
robot, then one for all robots, which starts the stepping) and the same 10,000-step event script: the
program's sensors, one byte a step in flash (program_script.h), levels held 1-4 steps in stormy
stretches so that contradictory inputs (highEnergy with lowEnergy, atWork with notAtWork...)
rise together, quiet stretches where the controllable events move the supervisors, and two
restarts (SCT_reset). The per-step logs (checks and callbacks in call order, the turns the
actions drew from rand_soft, the four supervisors' states) must be identical; a build of (b)
drawing from avr-libc's rand instead, and one robot of another uid, must differ."""

import os
import random
import re
import subprocess
import sys
from pathlib import Path

import pytest

from checkout import ROOT
from targets.kilobot.needs import board, board_or_skip, kilolib_or_skip

HERE = Path(__file__).resolve().parent / "published_style"
PROGRAM = HERE / "program.c"
SUPERVISOR = ROOT / "tests" / "corpus" / "openswarm" / "energy_worker.yaml"
PUBLISHED_VM = ROOT / "benchmarks" / "published_form" / "published_vm.c"
DOC = ROOT / "docs" / "robots" / "kilobot.md"
SECTION = "## Moving a published program over"
BEGIN, END = "/* --- SCT VM begin --- */\n", "/* --- SCT VM end --- */"
STEPS = 10_000
SEED = 35
RESTARTS = (STEPS // 2, STEPS * 3 // 4)
UID, OTHER_UID = 7, 8
EEPROM_UID = 0xB0               # kilolib: the robot's uid, low byte first
CONFIG, CHARGING, WORKING = 10, 119, 120
RUNNING = 12                    # the tick by which kilolib runs the program (tests/kilobot_stream_demo.py)
# Before the stepping: two neighbours' messages, ARK's configuration for robot 9 (goals 5 and 6:
# ignored, else the program would start at once with "goals 5 6 heard 2"), a third neighbour's
# message, then the configuration for all robots (data[0] 0xFF: goals 3 and 4).
MESSAGES = [(RUNNING, CHARGING, b"\x02"), (RUNNING + 1, WORKING, b"\x03"), (RUNNING + 2, CONFIG, b"\x09\x05\x06"),
            (RUNNING + 3, WORKING, b"\x04"), (RUNNING + 6, CONFIG, b"\xff\x03\x04")]
NO_END = 10 ** 7                # ticks: the program ends the run itself (cli; sleep) after its last step
SHORT = 60_000_000              # cycles: a run of some 1,500 steps, for the builds that must differ
# The uncontrollable events in the supervisor file's order (EV_highEnergy 2, EV_lowEnergy 5,
# EV_atWork 6 ... EV_notAtWork 9): the published VM polls them so, every step.
FILE_ORDER_CHECKS = "256789"
STEP = re.compile(r"(\d+):(\d*)((?: \d[LR]?)*) \| (\d+ \d+ \d+ \d+)\Z")
MOVES = {"0", "4"}              # EV_moveToCharge, EV_moveToWork: their actions draw a turn


# ---- the event script ---------------------------------------------------------------------------

def event_script(steps=STEPS, seed=SEED):
    """One byte a step, the program's sensors (program.c: bit 0 highEnergy ... bit 5 notAtWork,
    bit 6 restart). Stormy stretches: each level held 1-4 steps then drawn again, true with
    probability 1/2, so several rise together; quiet ones: the levels held."""
    rng = random.Random(seed)
    levels, hold, script = [0] * 6, [0] * 6, []
    while len(script) < steps:
        stormy = rng.random() < 0.6
        for _ in range(rng.randint(5, 60)):
            for k in range(6):
                if stormy and hold[k] == 0:
                    levels[k], hold[k] = rng.randrange(2), rng.randint(1, 4)
                hold[k] = max(hold[k] - 1, 0)
            script.append(sum(level << k for k, level in enumerate(levels)) | (0x40 if len(script) in RESTARTS else 0))
    return bytes(script[:steps])


def write_script(folder, script):
    rows = ",\n".join(", ".join("%d" % b for b in script[i:i + 24]) for i in range(0, len(script), 24))
    (folder / "program_script.h").write_text(
        "/* Written by tests/targets/kilobot/test_published_program.py: the sensors' levels, a byte a step. */\n"
        "#define PROGRAM_SCRIPT_STEPS %du\nstatic const uint8_t program_script[PROGRAM_SCRIPT_STEPS] PROGMEM = {\n%s\n};\n"
        % (len(script), rows))


# ---- the one file, and its move --------------------------------------------------------------------

def vm_section():
    """The published-form tables and VM as one piece of C: published_vm.c with its tables file's
    text (the defines above the arrays, as the inline layout) where it includes SCT_TABLES."""
    import nadzoru_c_form

    doc = nadzoru_c_form.read_yaml(SUPERVISOR)
    vm = PUBLISHED_VM.read_text()
    guard = re.findall(r"#ifndef SCT_TABLES\n#error[^\n]*\n#endif\n", vm)
    assert len(guard) == 1 and vm.count("#include SCT_TABLES\n") == 1, "published_vm.c changed its tables include"
    return vm.replace(guard[0], "").replace("#include SCT_TABLES\n", nadzoru_c_form.defines(doc) + nadzoru_c_form.tables(doc))


def published_program():
    text = PROGRAM.read_text()
    assert text.count(BEGIN) == 1 and text.count(END) == 1
    start, stop = text.index(BEGIN) + len(BEGIN), text.index(END)
    return text[:start] + vm_section() + text[stop:]


def doc_section():
    text = DOC.read_text()
    assert SECTION in text, "docs/robots/kilobot.md has no %r" % SECTION
    return text.split(SECTION, 1)[1].split("\n## ", 1)[0]


def doc_commands():
    """The section's ```sh commands, in order (continuation lines joined), the KILOLIB
    placeholder kept."""
    blocks = re.findall(r"^```sh\n(.*?)^```", doc_section(), re.M | re.S)
    return [c.strip() for block in blocks for c in re.sub(r"\\\n\s*", " ", block).splitlines()
            if c.strip() and not c.lstrip().startswith("#")]


def with_swarmvm():
    """The environment with the swarmvm of the Python running the tests first on PATH."""
    return dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent), os.environ.get("PATH", "")]))


def bash(commands, cwd):
    run = subprocess.run(["bash", "-c", "set -e -o pipefail\n" + "\n".join(commands)], cwd=cwd, capture_output=True,
                         text=True, timeout=300, env=with_swarmvm())
    assert run.returncode == 0, "\n".join(commands) + "\n" + run.stdout[-2000:] + run.stderr[-2000:]


def move_over(folder, script, kilolib, make_extra=""):
    """(b): the doc's commands run in ``folder`` holding the one-file program.c, the test's
    script header put beside the moved program (a robot's program has sensors instead) before
    the build; ``make_extra`` added to the doc's make line. The ELF."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "program.c").write_text(published_program())
    commands = doc_commands()
    cd = commands.index("cd kilobot_app")
    assert any(c.startswith("swarmvm gen program.c") for c in commands[:cd]), "the doc's steps generate nothing"
    assert any(c.startswith("make ") and "-DSVM_SCT_EXACT=1" in c for c in commands[cd:]), "no exact-mode build"
    bash(commands[:cd], folder)
    app = folder / "kilobot_app"
    write_script(app, script)
    make = [c.replace("KILOLIB=/path/to/kilolib", "KILOLIB=%s" % kilolib) + make_extra if c.startswith("make ") else c
            for c in commands[cd + 1:]]
    bash(make, app)
    (elf,) = app.glob("*.elf")
    return elf


def makefile_flags(app):
    """The generated Makefile's CFLAGS and LDFLAGS: how (a) is compiled, so that the two builds
    differ by their VMs only."""
    text = (app / "Makefile").read_text()
    flags = []
    for name in ("CFLAGS", "LDFLAGS"):
        for value in re.findall(r"^%s \+?= (.*)$" % name, text, re.M):
            flags += value.split()
    return flags


def build_published(folder, script, kilolib, flags):
    """(a): the one file with the published-form VM inline, drawing from rand_soft."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "program.c").write_text(published_program())
    write_script(folder, script)
    elf = folder / "published.elf"
    out = subprocess.run(["avr-gcc", *flags, "-DSCT_RANDOM=rand_soft", "-I%s" % kilolib, "program.c",
                          str(kilolib / "build" / "kilolib.a"), "-o", str(elf)], cwd=folder, capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr[-3000:]
    return elf


def eeprom(uid):
    data = bytearray(b"\xff" * 1024)
    data[EEPROM_UID:EEPROM_UID + 2] = uid.to_bytes(2, "little")
    return bytes(data)


def run(elf, uid=UID, cycles=None):
    result = board.run(elf, NO_END, MESSAGES, eeprom=eeprom(uid), cycles=cycles, timeout=300)
    assert result.end[2] == ("cycles" if cycles else "done"), result.end
    return result


def sizes(elf):
    """(flash, static RAM) of ``elf`` without the test's script: avr-size's text + data and
    data + bss, less the script's bytes (in flash, the same in both builds)."""
    out = subprocess.run(["avr-size", "-A", str(elf)], check=True, capture_output=True, text=True).stdout
    section = {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\.\w+)\s+(\d+)", out, re.M)}
    nm = subprocess.run(["avr-nm", "-S", str(elf)], check=True, capture_output=True, text=True).stdout
    script = next(int(line.split()[1], 16) for line in nm.splitlines() if line.endswith(" program_script"))
    return section[".text"] + section[".data"] - script, section[".data"] + section.get(".bss", 0)


def step_lines(lines):
    return [line for line in lines if STEP.match(line)]


def first_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return "line %d: %r != %r" % (i + 1, x, y)
    return "lengths %d != %d" % (len(a), len(b))


# ---- fixtures: each build and its full run made once ---------------------------------------------

@pytest.fixture(scope="module")
def script():
    return event_script()


@pytest.fixture(scope="module")
def kilolib():
    board_or_skip()
    return kilolib_or_skip()


@pytest.fixture(scope="module")
def moved(tmp_path_factory, script, kilolib):
    return move_over(tmp_path_factory.mktemp("moved"), script, kilolib)


@pytest.fixture(scope="module")
def published(tmp_path_factory, script, kilolib, moved):
    return build_published(tmp_path_factory.mktemp("published"), script, kilolib, makefile_flags(moved.parent))


@pytest.fixture(scope="module")
def published_run(published):
    return run(published)


@pytest.fixture(scope="module")
def moved_run(moved):
    return run(moved)


# ---- the tests ----------------------------------------------------------------------------------

def test_the_script_is_deterministic_long_and_contradictory(script):
    assert script == event_script() and len(script) >= 10_000 and event_script(seed=1) != script
    rises = [(script[k] & ~script[k - 1] & 0x3F, script[k]) for k in range(1, len(script))]
    # Several events rising in one step (their order of application shows), and contradictory
    # pairs (highEnergy+lowEnergy, atWork+notAtWork, atCharger+notAtCharger) high together as one
    # of them rises.
    assert sum(1 for r, _ in rises if bin(r).count("1") >= 2) > 500
    pairs = (0b000011, 0b100100, 0b011000)
    assert sum(1 for r, level in rises if any(r & p and level & p == p for p in pairs)) > 1000
    assert [k for k, b in enumerate(script) if b & 0x40] == list(RESTARTS)


def test_the_published_program_is_one_file_holding_its_vm():
    one = published_program()
    section = one[one.index(BEGIN):one.index(END)]
    for piece in ("#define EV_moveToCharge 0", "sup_data[", "unsigned long int       sup_current_state[4]",
                  "void SCT_run_step(void)", "static unsigned char input_ring[INPUT_RING];"):
        assert piece in section, piece
    assert "#include SCT_TABLES" not in one and "#error" not in section
    # Its own includes only: kilolib's, avr-libc's and the test's script.
    assert set(re.findall(r'^#include ([<"][^>"]+[>"])', one, re.M)) == \
        {"<kilolib.h>", "<avr/pgmspace.h>", "<avr/sleep.h>", "<debug.h>", '"program_script.h"', "<stdlib.h>"}


@pytest.mark.emulator
@pytest.mark.slow
def test_the_published_form_vm_runs_the_program(published_run):
    """(a) in simavr: the whole script stepped after this robot's configuration, every step
    polling in the file's event order, contradictory inputs applied together, both restarts."""
    lines = published_run.lines
    steps = step_lines(lines)
    assert [int(STEP.match(s).group(1)) for s in steps] == list(range(STEPS))
    # The configuration for all robots, not robot 9's; the three neighbours' messages heard before it.
    assert lines[0] == "goals 3 4 heard 3" and lines[-1].startswith("end ")
    assert lines.count("reset") == 2
    assert all(STEP.match(s).group(2) == FILE_ORDER_CHECKS for s in steps)
    callbacks = [STEP.match(s).group(3).split() for s in steps]
    assert sum(1 for c in callbacks if len(c) >= 3) > 300            # inputs together, then the draw
    assert sum(1 for c in callbacks if any(e[0] in MOVES for e in c)) > 300
    assert len({STEP.match(s).group(4) for s in steps}) >= 10
    # Its own messages went out, as working and as charging.
    assert {m.type for m in published_run.tx if m.ok} == {CHARGING, WORKING}


@pytest.mark.emulator
@pytest.mark.slow
def test_moved_over_by_the_docs_steps_swarmvm_in_exact_mode_logs_the_same(published_run, moved_run):
    """(b): the same program moved over as the doc says, same kilo_uid, same messages, same
    script: the same 10,000-step log, line for line."""
    assert moved_run.lines == published_run.lines, first_difference(moved_run.lines, published_run.lines)


def test_the_tables_read_from_the_program_are_the_supervisors(moved, tmp_path):
    """`swarmvm gen program.c` took the tables from the program's own arrays: the image is the
    one generated from the supervisor file."""
    out = subprocess.run(["swarmvm", "gen", str(SUPERVISOR), "--target", "kilobot", "--name", "worker", "-o",
                          str(tmp_path)], capture_output=True, text=True, env=with_swarmvm())
    assert out.returncode == 0, out.stderr
    assert (moved.parent / "worker.svm").read_bytes() == (tmp_path / "worker.svm").read_bytes()


@pytest.mark.emulator
@pytest.mark.slow
def test_both_draw_from_rand_soft(tmp_path, script, kilolib, published_run):
    """The same move built with the VM drawing from avr-libc's rand instead (`SVM_SCT=`: no
    -DSVM_SCT_RANDOM=rand_soft, so exact mode's default, rand): the program's own draws from
    rand_soft (its turns) come out otherwise, so the logs above agree because both VMs draw from
    rand_soft, taking their draws out of the program's sequence."""
    elf = move_over(tmp_path / "rand", script, kilolib, make_extra=" SVM_SCT=")
    lines = step_lines(run(elf, cycles=SHORT).lines)[:-1]
    assert len(lines) > 1000
    assert lines != step_lines(published_run.lines)[:len(lines)]


@pytest.mark.emulator
@pytest.mark.slow
def test_another_robot_draws_otherwise(moved, published_run):
    """(b) on robot 8, the same messages and script: its program seeds rand_soft from its uid,
    so its turns differ from robot 7's on the same inputs (the VM's draws come from the same
    sequence, but in this model they never have a choice: the test below)."""
    lines = step_lines(run(moved, uid=OTHER_UID, cycles=SHORT).lines)[:-1]
    mine = step_lines(published_run.lines)[:len(lines)]
    assert len(lines) > 1000 and lines != mine
    # The same inputs: every step polled alike; only the draws (turns, choices) differ.
    assert [STEP.match(s).group(2) for s in lines] == [STEP.match(s).group(2) for s in mine]


def test_the_docs_figures_are_the_measured_ones(published, moved):
    """The flash and RAM the doc states for (a) and (b), from avr-size of these builds."""
    table = dict(re.findall(r"^\| (published-form VM inline|swarmvm, exact mode) \| ([\d,]+ B \| [\d,]+ B) \|",
                            doc_section(), re.M))
    for row, elf in (("published-form VM inline", published), ("swarmvm, exact mode", moved)):
        flash, ram = sizes(elf)
        measured = "%s B | %s B" % (format(flash, ","), format(ram, ","))
        assert table.get(row) == measured, "docs/robots/kilobot.md, %r: measured %s" % (row, measured)


def test_in_this_model_the_draw_never_has_a_choice():
    """Why the logs show the draw only through the program's own rand_soft draws: of the joint
    states the published tables reach (uncontrollable events anywhere, enabled controllable
    ones), none enables more than one controllable event, so RANDOM() % n is 0; the published
    VM still calls RANDOM() on every step that has one enabled, taking it out of rand_soft's
    sequence."""
    import nadzoru_c_form

    doc = nadzoru_c_form.read_yaml(SUPERVISOR)
    number = {name: i for i, name in enumerate(doc["events"])}
    data = [number[x] if x in number else int(x) for x in doc["sup_data"]]
    first = [int(x) for x in doc["sup_data_pos"]]
    alphabet = [[int(x) for x in row] for row in doc["sup_events"]]
    controllable = [int(x) for x in doc["ev_controllable"]]
    sups, events = range(len(first)), range(len(number))

    def moves(sup, state):
        at = first[sup]
        for _ in range(state):
            at += 1 + 3 * data[at]
        return {data[at + 1 + 3 * k]: data[at + 2 + 3 * k] * 256 + data[at + 3 + 3 * k] for k in range(data[at])}

    def enabled(joint):
        return [e for e in events if controllable[e] and all(not alphabet[s][e] or e in moves(s, joint[s]) for s in sups)]

    start = tuple(int(x) for x in doc["sup_init_state"])
    seen, todo, most = {start}, [start], 0
    while todo:
        joint = todo.pop()
        most = max(most, len(enabled(joint)))
        for e in events:
            if controllable[e] and e not in enabled(joint):
                continue
            after = tuple(moves(s, joint[s]).get(e, joint[s]) if alphabet[s][e] else joint[s] for s in sups)
            if after not in seen:
                seen.add(after)
                todo.append(after)
    assert (len(seen), most) == (36, 1)
