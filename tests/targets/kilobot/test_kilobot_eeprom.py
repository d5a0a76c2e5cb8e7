"""Nothing swarmvm runs on a Kilobot writes EEPROM where kilolib keeps the robot's calibration
(0x01-0xB1: OSCCAL, motors, IR, TX mask, UID; runtime_c/swarmvm_kilobot_eeprom.h). In simavr
on the Kilobot board, with a calibrated robot's EEPROM (random bytes there) dumped before and
after: the generated application writes no EEPROM at all, and the conformance harness's EEPROM
pass puts the image at SVM_KILOBOT_EEPROM_FREE and runs it from there."""

import random

import pytest

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import SUPERVISORS, batch
from targets.kilobot.needs import board, board_or_skip
from kilobot_stream_demo import SUPERVISOR_B, Program
from swarmvm.compiler.pipeline import compile_inputs

EEPROM_BYTES = 1024


def calibrated_eeprom():
    """A robot's EEPROM: kilolib's area filled (random, fixed seed), the rest erased."""
    area = random.Random(11).randbytes(c_harness.eeprom_image_at())
    return area + b"\xff" * (EEPROM_BYTES - len(area))


def test_the_first_free_address_is_past_kilolibs_calibration():
    assert c_harness.eeprom_image_at() == 0xB2      # kilolib's UID ends at 0xB1


@pytest.mark.emulator
def test_the_application_leaves_the_eeprom_alone(tmp_path):
    board_or_skip()
    program = Program(tmp_path)
    image_b = compile_inputs([str(SUPERVISOR_B)]).image     # a stream too: it lands in RAM
    before = calibrated_eeprom()
    result = board.run(program.elf, 80, program.stream(image_b, 12), eeprom=before)
    assert result.end[0] == 80 and any(line.startswith("swap ok") for line in result.lines)
    assert result.eeprom == before


@pytest.mark.emulator
def test_the_harness_writes_its_image_above_kilolibs_area(tmp_path):
    board_or_skip()
    b = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    elf, loaded = c_harness.build_avr(b, tmp_path, eeprom=True)
    before = calibrated_eeprom()
    result = board.run(elf, None, eeprom=before)
    at = c_harness.eeprom_image_at()
    assert result.end[2] == "done"
    assert result.eeprom[:at] == before[:at]                                  # 0x00-0xB1 untouched
    assert result.eeprom[at:at + len(b.image)] == b.image                     # the image, from 0xB2
    assert result.eeprom[at + len(b.image):] == before[at + len(b.image):]
    traces, info = c_harness.parse("\n".join(result.lines) + "\n")
    assert 2 in {p for p, _ in traces}
    assert mismatches(b, traces, info, (0,) + ((1,) if loaded else ()) + (2,)) == []
