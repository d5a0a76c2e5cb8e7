"""A generated Kilobot application with the learned policy (`make LEARNED=1`, real kilolib,
simavr Kilobot board) keeps what it learned across a reset: run 1 starts from a robot's EEPROM
with no record, learns from its controller's rewards and saves on its cadence; run 2 boots the
MCU again with the EEPROM run 1 left, and the parameters after start-up (printed by the first
action, before its reward) are exactly the newest record in that EEPROM, decoded here
independently of the C code (docs/learning.md, "Keeping them across power cuts").

The program: examples/learning's forager (6 controllable events, 2 supervisors), built with its
generated Makefile, a controller rewarding each event as benchmarks/learning.py's operator does
(without the noise), and SVM_KILOBOT_KEEP_EVERY=64 so that a few hundred steps save several
times."""

import random
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from targets.kilobot.needs import board, board_or_skip, kilolib_or_skip
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.runtime_files import RUNTIME_PY_DIR
from swarmvm.targets import generate

sys.path.insert(0, str(RUNTIME_PY_DIR))
from swarmvm_format import crc16  # noqa: E402

ROOT = Path(__file__).resolve().parents[3]
FORAGER = ROOT / "examples" / "learning" / "supervisor.yaml"
NAME = "forager"
REWARDS = {"near": 1.5, "far": 4.0, "wait": -0.1, "walk": -1.0, "run": -2.0, "charge": -0.5}
KEEP_EVERY = 64
EEPROM_FREE = 0xB2          # swarmvm_kilobot_eeprom.h
EEPROM_BYTES = 1024
COMMITTED = 0x5A

CONTROLLER = r"""/* Test controller: rewards each event; the first action prints the parameters it starts with
 * ("start UPDATES BASELINE THETA..." in hex) before crediting anything. */
#define DEBUG
#include "kilolib.h"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"   /* kilolib's debug.h, under -Wextra */
#include "debug.h"
#pragma GCC diagnostic pop
#include "%(name)s_tables.h"
#include "%(name)s_app.h"

static uint8_t printed;

static void put_hex(uint32_t v)
{
    static const char digits[] = "0123456789abcdef";
    int8_t shift;
    putchar(' ');
    for (shift = 28; shift >= 0; shift -= 4) {
        putchar(digits[(v >> shift) & 15u]);
    }
}

static void act(int32_t reward)
{
    if (!printed) {
        const svl_policy_t *p = svm_kilobot_keeper()->policy;
        uint16_t i;
        debug_init();
        printed = 1;
        printf("start");
        put_hex(p->updates);
        put_hex((uint32_t)p->baseline);
        for (i = 0; i < p->num_theta; i++) {
            put_hex((uint32_t)p->theta[i]);
        }
        putchar('\n');
    }
    svm_kilobot_reward(reward);
}

void %(name)s_stream_status(uint8_t status, uint16_t value)
{
    (void)status;
    (void)value;
}
%(actions)s"""


def controller_source():
    actions = "".join("\nvoid %s_on_%s(void)\n{\n    act(SVL_Q16(%r));\n}\n" % (NAME, event, value)
                      for event, value in REWARDS.items())
    return CONTROLLER % dict(name=NAME, actions=actions)


def build(workdir: Path, kilolib: Path) -> Path:
    """The forager's Kilobot application, built with its generated Makefile (LEARNED=1)."""
    write_outputs(workdir, generate(compile_inputs([str(FORAGER)], name=NAME), "kilobot"))
    (workdir / ("%s_controller.c" % NAME)).write_text(controller_source())
    subprocess.run(["make", "LEARNED=1", "KILOLIB=%s" % kilolib, "CPPFLAGS=-DSVM_KILOBOT_KEEP_EVERY=%d" % KEEP_EVERY,
                    "%s.elf" % NAME], cwd=workdir, check=True, capture_output=True, text=True)
    return workdir / ("%s.elf" % NAME)


def newest_record(eeprom: bytes, slot_size: int):
    """(sequence, words) of the newest committed slot with a good CRC (write block 1: state,
    sequence u32, length u16, payload, CRC-16 over sequence..payload), or None."""
    best = None
    for slot in (0, 1):
        at = EEPROM_FREE + slot * slot_size
        if eeprom[at] != COMMITTED:
            continue
        sequence, length = struct.unpack_from("<IH", eeprom, at + 1)
        body = eeprom[at + 1:at + 7 + length]
        if struct.unpack_from("<H", eeprom, at + 7 + length)[0] != crc16(body):
            continue
        if best is None or ((sequence - best[0]) & 0xFFFFFFFF) < 0x80000000:
            best = (sequence, struct.unpack("<%dI" % (length // 4), body[6:]))
    return best


def start_line(run):
    line = next(line for line in run.lines if line.startswith("start"))
    return [int(word, 16) for word in line.split()[1:]]


@pytest.mark.emulator
@pytest.mark.slow
def test_learned_parameters_survive_a_reset(tmp_path):
    board_or_skip()
    elf = build(tmp_path, kilolib_or_skip())
    theta = 5 * 6                                   # states x controllable events
    slot_size = 1 + 4 + 2 + 4 * (8 + theta + 1) + 2
    calibration = random.Random(12).randbytes(EEPROM_FREE)
    erased = calibration + b"\xff" * (EEPROM_BYTES - EEPROM_FREE)

    first = board.run(elf, 400, eeprom=erased)
    assert start_line(first) == [0, 0] + [0] * theta, "no record: the initial parameters (all 0)"
    record = newest_record(first.eeprom, slot_size)
    assert record is not None, "run 1 saved nothing"
    sequence, words = record
    assert sequence >= 2                            # saved several times, slots alternating
    assert words[:3] == (0x53564C50, 1, theta) and words[7] >= 3 * KEEP_EVERY
    assert any(words[8:8 + theta]), "it learned something"
    assert first.eeprom[:EEPROM_FREE] == calibration   # kilolib's calibration untouched

    second = board.run(elf, 40, eeprom=first.eeprom)   # the MCU boots again on that EEPROM
    updates, baseline, *preferences = start_line(second)
    assert (updates, baseline, tuple(preferences)) == (words[7], words[6], words[8:8 + theta])
