"""The Kilobot application on the real kilolib, in simavr (firmware/kilobot/board.py): what makes
it correct on a real robot (runtime_c/swarmvm_kilobot.h).

- the VM steps at its documented rate, once per kilolib tick (or every
  SVM_KILOBOT_TICKS_PER_STEP ticks), driven by kilolib's Timer0 interrupt during the main loop;
- messages flow both ways while the loop runs: every message received at kilolib's rate makes
  its event occur exactly once, at the next step; every message the robot sends is whole (CRC
  good) and carries a public event that fired, one per kilolib transmission slot, none skipped;
- the variables shared with kilolib's interrupts are volatile and taken under ATOMIC_BLOCK
  (checked on the source: a data race does not show on every run).

Programs: supervisor A (hitl_leader) with the trace-printing test controller of
tests/kilobot_stream_demo.py."""

import re

import pytest

from targets.kilobot.needs import kilolib_or_skip
from kilobot_stream_demo import RUNNING, Program, reference, split
from swarmvm.compiler.runtime_files import RUNTIME_C

NORMAL = 0
TX_PERIOD_TICKS = 16        # kilolib: kilo_tx_period 3906 Timer0 counts, 255 per tick


@pytest.fixture(scope="module")
def program(tmp_path_factory):
    kilolib_or_skip()
    return Program(tmp_path_factory.mktemp("kilobot_runtime"))


def first_tick(lines):
    return next(int(line.split()[1]) for line in lines if line.startswith("first "))


@pytest.mark.emulator
@pytest.mark.slow
def test_the_vm_steps_once_per_kilolib_tick(program, tmp_path):
    result = program.run([], 200)
    steps, _, _, _ = split(result.lines)
    assert result.end[0] == 200
    # Step 1 ran at tick `first`, and one step followed every tick up to the last.
    assert len(steps) in (200 - first_tick(result.lines), 200 - first_tick(result.lines) + 1)
    slower = Program(tmp_path, defines=["-DSVM_KILOBOT_TICKS_PER_STEP=4"])
    result = slower.run([], 200)
    steps, _, _, _ = split(result.lines)
    assert abs(len(steps) - (200 - first_tick(result.lines)) / 4) <= 1


@pytest.mark.emulator
@pytest.mark.slow
def test_messages_in_both_directions_none_lost(program):
    # "requestL" (received: EV__requestL) every 2 ticks, while the program also sends its own.
    sent = [(RUNNING + 2 * k, NORMAL, b"requestL\0") for k in range(40)]
    result = program.run(sent, RUNNING + 2 * 40 + 40)
    lines = result.lines
    before, swap, _, _ = split(lines)
    assert swap is None
    assert [m.data for m in result.rx[1:]] == [m[2] for m in sent]       # the board sent them all
    received = [(Program.step_of(lines, m.tick), "EV__requestL") for m in result.rx[1:]]
    assert len({step for step, _ in received}) == len(sent)
    # Each one made EV__requestL occur once, at the step after it came: A's reference trace.
    assert before == reference(program.compiled, program.compiled.image, 0, len(before), received=received)
    assert sum("EV__requestL" in line for line in before) == len(sent)
    # What the robot sent: whole messages (kilolib's CRC good), each a public controllable
    # event of A's that fired before, at most one per transmission slot.
    assert result.tx and all(m.ok and m.type == NORMAL for m in result.tx)
    first = first_tick(lines)
    for m in result.tx:
        name = m.data.rstrip(b"\0").decode()
        fired_before = before[:m.tick - first + 1]
        assert any(re.search(r"\bEV_%s\b" % name, line) for line in fired_before), name
    assert all(b.tick - a.tick >= TX_PERIOD_TICKS - 1 for a, b in zip(result.tx, result.tx[1:]))
    # None skipped: every public event that fired one slot or more before the end went out.
    model = program.compiled.model
    sends = {"EV_" + e for k, e in enumerate(model.events) if model.public[k] and model.controllable[k]}
    fired = {e[3:] for line in before[:-2 * TX_PERIOD_TICKS] for e in line.split()[1].split(",") if e in sends}
    assert len(fired) >= 2 and fired <= {m.data.rstrip(b"\0").decode() for m in result.tx}


SHARED = ("received", "pending", "chunk_slot", "chunk_head", "chunk_tail", "from_stream", "held")


def test_variables_shared_with_interrupts_are_volatile_and_taken_atomically():
    source = (RUNTIME_C / "swarmvm_kilobot.c").read_text()
    for name in SHARED:
        declaration = re.search(r"^static (volatile )?uint8_t [^;]*\b%s\b" % name, source, re.M)
        assert declaration and declaration.group(1), name
    # loop()'s side: every read-modify-write of `received` and every read of kilo_ticks and the
    # chunk ring sits in an ATOMIC_BLOCK.
    for function in ("svm_kilobot_send", "svm_kilobot_take", "take_chunk", "now"):
        body = re.search(r"\n[^\n]*\b%s\([^)]*\)\n\{(.*?)\n\}" % function, source, re.S).group(1)
        assert "ATOMIC_BLOCK(ATOMIC_RESTORESTATE)" in body, function
    assert "#include <util/atomic.h>" in source
