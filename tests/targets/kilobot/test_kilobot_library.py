"""The Kilobot runtime is a library the program calls (issue 35, point 2; runtime_c/swarmvm_kilobot.h,
docs/robots/kilobot.md, "Using swarmvm from your own program"). On the real kilolib in simavr
(firmware/kilobot/board.py), supervisor A (hitl_leader) built by its generated Makefile:

- with the generated main (``robot_main.c``): every message the VM does not take (ARK's
  configuration type 10, a program's types 119 and 120, a NORMAL one naming no event) reaches the
  controller's ``svm_kilobot_on_message``; the VM's seed is the robot's, from kilo_uid (EEPROM
  0xB0-0xB1): two uids make different choices on the same inputs, one uid twice the same, each
  the Python reference's with ``uid_seed(uid)``; ``SVM_KILOBOT_SEED_RAND_HARD`` seeds from
  rand_hard instead;
- with a program's own main (``make MAIN=program.c``): its own setup, loop and kilolib message
  callbacks calling svm_kilobot_begin/poll/receive/transmit/transmitted; it holds the VM until
  ARK's configuration says the goals are set, sets options and seed from its code, receives every
  message first, and shares the transmission slots with the VM;
- the robot page's own program (docs/robots/kilobot.md, "Using swarmvm from your own program"),
  as the page shows it, with the generated controller: ``make MAIN=my_program.c``.

The trace lines are the test controller's of tests/kilobot_stream_demo.py; each message's data[0]
is printed with its type ("own TYPE BYTE": the hook; "mine TYPE BYTE": the program's handler)."""

import re
import shutil
import subprocess

import pytest

from kilobot_stream_demo import NAME, RUNNING, SUPERVISOR_A, controller_source, reference, split
from checkout import EXAMPLE, ROOT
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import generate
from swarmvm.targets.kilobot import uid_seed
from targets.kilobot.needs import board, board_or_skip, kilolib_or_skip

NORMAL, CONFIG, OWN_A, OWN_B = 0, 10, 119, 120
EEPROM_UID = 0xB0               # kilolib: the robot's uid, low byte first
WARNINGS = "-Wextra -Werror -pedantic"
# The same inputs for every run: a public event's message, then the others, one each 2 ticks.
MESSAGES = [(RUNNING, OWN_A, b"\x07"), (RUNNING + 2, NORMAL, b"requestL\0"), (RUNNING + 4, CONFIG, b"\x00"),
            (RUNNING + 6, NORMAL, b"nobody\0"), (RUNNING + 20, CONFIG, b"\x01"), (RUNNING + 24, OWN_B, b"\x09")]
NOT_THE_VMS = [(t, d[0]) for _, t, d in MESSAGES if d != b"requestL\0"]      # in the order sent
TICKS = RUNNING + 60

# What the controller adds: the hook records what it is given (in the IR interrupt), the step
# prints it (in loop) before the trace line, and keeps the VM's seed where the board reads it.
HOOK = r"""
static volatile uint8_t kept_type[8], kept_byte[8], kept;
static uint8_t shown;
uint32_t seen_seed;

void svm_kilobot_on_begin(void)
{
    put_text("begun\n");
}

void svm_kilobot_on_message(message_t *message, distance_measurement_t *distance)
{
    (void)distance;
    if (kept < 8u) {
        kept_type[kept] = message->type;
        kept_byte[kept] = message->data[0];
        kept++;
    }
}

void svm_kilobot_after_step(void)
{
    while (shown < kept) {
        put_text("own ");
        put_uint(kept_type[shown]);
        put_char(' ');
        put_uint(kept_byte[shown]);
        put_char('\n');
        shown++;
    }
    seen_seed = svm_kilobot_vm()->seed;
    trace_step();
}
"""

# A program with its own main, as a published one is: swarmvm is called, never in charge.
PROGRAM = r"""/* Test program with its own main (tests/targets/kilobot/test_kilobot_library.py). */
#include <stdio.h>
#include "kilolib.h"
#include "swarmvm_kilobot.h"

/* kilolib's debug.h (USART0 as stdout) defines it, in the test controller. */
void debug_init(void);

#define CONFIG 10u      /* ARK's configuration message; data[0] 1: the goals are set */
#define KEPT 8u

static volatile uint8_t mine_type[KEPT], mine_byte[KEPT], mine;
static uint8_t printed;
static volatile uint8_t offered_vms;    /* the message offered in this slot is the VM's */
static message_t own;

static void on_message(message_t *message, distance_measurement_t *distance)
{
    if (svm_kilobot_receive(message, distance)) {
        return;
    }
    if (message->type == CONFIG && message->data[0] == 1u) {
        svm_kilobot_hold(0);
    }
    if (mine < KEPT) {
        mine_type[mine] = message->type;
        mine_byte[mine] = message->data[0];
        mine++;
    }
}

static message_t *message_tx(void)
{
    message_t *vms = svm_kilobot_transmit();
    offered_vms = (uint8_t)(vms != 0);
    return vms != 0 ? vms : &own;
}

static void message_tx_success(void)
{
    if (offered_vms) {
        svm_kilobot_transmitted();
    }
}

static void setup(void)
{
    debug_init();
    own.type = 120u;
    own.data[0] = 42u;
    own.crc = message_crc(&own);
    svm_kilobot_hold(1);
    if (svm_kilobot_begin() != SVM_OK) {
        printf("refused\n");
    }
    svm_kilobot_set_options(SVM_INPUTS_EDGE, 12345u);
}

static void loop(void)
{
    while (printed < mine) {
        printf("mine %u %u\n", mine_type[printed], mine_byte[printed]);
        printed++;
    }
    svm_kilobot_poll();
}

int main(void)
{
    kilo_init();
    kilo_message_rx = on_message;
    kilo_message_tx = message_tx;
    kilo_message_tx_success = message_tx_success;
    kilo_start(setup, loop);
    return 0;
}
"""


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    """The generated application of A with the test controller and its hook."""
    board_or_skip()
    folder = tmp_path_factory.mktemp("kilobot_library")
    compiled = compile_inputs([str(SUPERVISOR_A)], name=NAME)
    write_outputs(folder, generate(compiled, "kilobot"))
    controller = controller_source(compiled).replace("void svm_kilobot_after_step(void)\n{",
                                                     "static void trace_step(void)\n{")
    (folder / ("%s_controller.c" % NAME)).write_text(controller + HOOK)
    (folder / "program.c").write_text(PROGRAM)
    return compiled, folder


def build(folder, into, *args, defines=""):
    """``make robot.elf`` with ``args`` and CPPFLAGS ``defines`` in a copy of ``folder``: the ELF."""
    shutil.copytree(folder, into)
    result = subprocess.run(["make", "-s", "KILOLIB=%s" % kilolib_or_skip(), "CPPFLAGS=%s %s" % (defines, WARNINGS), *args,
                             "%s.elf" % NAME], cwd=into,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    return into / ("%s.elf" % NAME)


def eeprom(uid):
    """An erased EEPROM but for the robot's uid."""
    data = bytearray(b"\xff" * 1024)
    data[EEPROM_UID:EEPROM_UID + 2] = uid.to_bytes(2, "little")
    return bytes(data)


def kept(lines, tag):
    return [tuple(map(int, line.split()[1:])) for line in lines if line.startswith(tag + " ")]


@pytest.fixture(scope="module")
def skeleton(app, tmp_path_factory):
    return build(app[1], tmp_path_factory.mktemp("skeleton") / "app")


@pytest.mark.emulator
def test_the_generated_main_gives_every_other_message_to_the_hook(skeleton):
    result = board.run(skeleton, TICKS, MESSAGES)
    assert kept(result.lines, "own") == NOT_THE_VMS
    # svm_kilobot_on_begin ran once, in setup, before the first step.
    first = next(i for i, line in enumerate(result.lines) if line.startswith("first "))
    assert result.lines.count("begun") == 1 and result.lines.index("begun") < first
    # requestL was the VM's: EV__requestL occurred once, at the step after it came.
    before, _, _, _ = split(result.lines)
    assert sum("EV__requestL" in line for line in before) == 1


@pytest.mark.emulator
def test_each_robot_draws_from_its_own_seed(app, skeleton):
    compiled, _ = app
    traces = {}
    for run, uid in enumerate((5, 6, 5, 0)):
        result = board.run(skeleton, TICKS, MESSAGES, eeprom=eeprom(uid), read="seen_seed")
        before, _, _, _ = split(result.lines)
        assert result.ram == uid_seed(uid) and uid_seed(uid) != 0
        received = [(i, "EV__requestL") for i, line in enumerate(before) if "EV__requestL" in line]
        assert before == reference(compiled, compiled.image, 0, len(before), received=received, uid=uid)
        traces[(uid, run)] = before
    assert traces[(5, 0)] == traces[(5, 2)]
    assert traces[(5, 0)] != traces[(6, 1)] and traces[(5, 0)] != traces[(0, 3)]


@pytest.mark.emulator
def test_rand_hard_seeds_on_request(app, tmp_path):
    compiled, folder = app
    elf = build(folder, tmp_path / "app", defines="-DSVM_KILOBOT_SEED=SVM_KILOBOT_SEED_RAND_HARD")
    result = board.run(elf, TICKS, MESSAGES, eeprom=eeprom(5), read="seen_seed")
    before, _, _, _ = split(result.lines)
    assert len(before) > 20 and result.ram != uid_seed(5)
    received = [(i, "EV__requestL") for i, line in enumerate(before) if "EV__requestL" in line]
    assert before == reference(compiled, compiled.image, 0, len(before), received=received, seed=result.ram)


@pytest.mark.emulator
def test_a_program_with_its_own_main_holds_configures_and_shares_the_channel(app, tmp_path):
    compiled, folder = app
    elf = build(folder, tmp_path / "app", "MAIN=program.c")
    result = board.run(elf, TICKS, MESSAGES, read="seen_seed")
    lines = result.lines
    # Its own handler had every message the VM did not take, first (and the hook too).
    assert kept(lines, "mine") == NOT_THE_VMS and kept(lines, "own") == NOT_THE_VMS
    # Held until the configuration with data[0] 1 came: the first step is at that tick or the next.
    released = next(m.tick for m in result.rx if m.type == CONFIG and m.data[0] == 1)
    first = next(int(line.split()[1]) for line in lines if line.startswith("first "))
    assert first in (released, released + 1)
    # Its options and seed (edge inputs, 12345); requestL, received while held, counts once at
    # the first step.
    before, _, _, _ = split(lines)
    assert result.ram == 12345 and len(before) >= TICKS - first - 1
    assert before == reference(compiled, compiled.image, 0, len(before), received=[(0, "EV__requestL")],
                               inputs="edge", seed=12345)
    # The slots: its own message (type 120) while the VM has none, the VM's public events after.
    assert result.tx and all(m.ok for m in result.tx)
    assert {m.type for m in result.tx} == {NORMAL, OWN_B}
    assert all(m.type == OWN_B and m.data[0] == 42 for m in result.tx if m.tick < first)


PAGE = ROOT / "docs" / "robots" / "kilobot.md"


@pytest.mark.emulator
def test_the_robot_pages_program_builds_and_waits_for_its_configuration(tmp_path):
    board_or_skip()
    program = re.search(r"^```c\n(/\* my_program\.c.*?)^```", PAGE.read_text(), re.M | re.S).group(1)
    folder = tmp_path / "gen"
    write_outputs(folder, generate(compile_inputs([str(EXAMPLE)], name=NAME), "kilobot"))     # the page's model
    (folder / "my_program.c").write_text(program)
    elf = build(folder, tmp_path / "app", "MAIN=my_program.c")
    messages = [(RUNNING, OWN_A, b"\x07"), (RUNNING + 20, CONFIG, b"\x01")]
    result = board.run(elf, RUNNING + 50, messages, step_pc=function_address(elf, "svm_step"))
    configured = next(m.tick for m in result.rx if m.type == CONFIG)
    # No step before the configuration came, then one per tick to the end.
    assert result.end[0] - configured - 1 <= len(result.steps) <= result.end[0] - configured + 1
    # Its own message went out while the VM had none to send (this model has no public event).
    assert result.tx and all(m.ok and m.type == OWN_B for m in result.tx)


def function_address(elf, name):
    """The flash byte address of function ``name`` of ``elf`` (avr-nm)."""
    out = subprocess.run(["avr-nm", str(elf)], check=True, capture_output=True, text=True).stdout
    return next(int(line.split()[0], 16) for line in out.splitlines() if line.split()[1:] == ["T", name])
