"""The learned-parameter store (runtime_c/swarmvm_store.c): a power cut at any point of a save
leaves the old record or the new one, never a mixture. The probe (c/store_probe.c) cuts the
medium's writes after k operations for every k across a whole save, with no, one and two
records saved before, on a simulated EEPROM and a simulated flash page (erase, then writes
that only clear bits; write blocks of 1 and 4 bytes, each block programmed once) on the host,
and on the ATmega328P's real EEPROM in simavr. A write is cut at every byte, also inside a
block. The CapBot's binding (runtime_c/swarmvm_store_zephyr.c, Zephyr's flash map API) is cut
the same way on a Cortex-M4F in QEMU (mps2-an386), over the stand-in partition of
firmware/capbot/flash_qemu.c (NOR rules of the nRF52840: 4 KB pages, aligned 32-bit words)."""

import re

import pytest

import learnbuild
from conformance import qemu_harness

SOURCES = [learnbuild.RUNTIME_C / "swarmvm.c", learnbuild.RUNTIME_C / "swarmvm_store.c",
           learnbuild.PROBES / "store_probe.c"]
NEW_RECORD = 16           # bytes of the probe's record 3, saved under the cut
BLOCKS = {"eeprom": 1, "flash": 1, "flash4": 4, "zephyr": 4}


def committed_at(block):
    """Operations of a save up to and including the commit byte: the erase (or the empty mark's
    block), the body (sequence, length, payload, CRC) padded to whole blocks, then the commit
    byte, the first of the state block."""
    mark = 1 if block == 1 else block      # EEPROM marks empty by writing; flash erases (1 operation)
    return (1 if block > 1 else mark) + -(-(8 + NEW_RECORD) // block) * block + 1


def outcomes(text):
    """{(medium, prior records, k): (outcome, block)} and the bit-rot outcome from the probe's
    output; no misuse of the flash (unaligned writes, a byte programmed twice)."""
    cuts = {(medium, int(prior), int(k)): (outcome, int(block))
            for medium, prior, k, outcome, block in re.findall(r"cut (\w+) (\d+) (\d+) (\w+) (\d+)", text)}
    assert "end" in text.split()
    assert re.search(r"misuse (\d+)", text).group(1) == "00"
    return cuts, re.search(r"rot (\w+)", text).group(1)


def check(cuts, media):
    """Before the commit byte the load gives the record saved before (none when there was
    none), from it on the new one; every k from 0 to past the save is there."""
    for medium in media:
        block = BLOCKS[medium]
        last = block + -(-(8 + NEW_RECORD) // block) * block + 2
        for prior in (0, 1, 2):
            for k in range(last + 1):
                expected = "new" if k >= committed_at(block) else "old" if prior else "none"
                assert cuts[(medium, prior, k)] == (expected, block), (medium, prior, k)
    assert len(cuts) == sum(3 * (BLOCKS[m] + -(-(8 + NEW_RECORD) // BLOCKS[m]) * BLOCKS[m] + 3) for m in media)


def test_a_cut_save_loads_the_old_or_the_new_record_on_the_host(tmp_path):
    exe = learnbuild.build_host(tmp_path / "store_probe", SOURCES, defines=())
    cuts, rot = outcomes(learnbuild.run_host(exe))
    check(cuts, ("eeprom", "flash", "flash4"))
    assert rot == "old"


@pytest.mark.emulator
def test_a_cut_save_loads_the_old_or_the_new_record_on_the_avr_eeprom(tmp_path):
    elf = learnbuild.build_avr(tmp_path / "store_probe.elf", SOURCES)
    cuts, rot = outcomes(learnbuild.run_simavr(elf))
    check(cuts, ("eeprom",))
    assert rot == "old"


@pytest.mark.emulator
def test_a_cut_save_loads_the_old_or_the_new_record_on_the_capbot_flash_in_qemu(tmp_path):
    capbot = qemu_harness.CAPBOT
    elf = qemu_harness.compile_m4(
        [learnbuild.RUNTIME_C / "swarmvm.c", learnbuild.RUNTIME_C / "swarmvm_store.c",
         learnbuild.RUNTIME_C / "swarmvm_store_zephyr.c", capbot / "flash_qemu.c", learnbuild.PROBES / "store_probe.c"],
        tmp_path / "store_probe.elf", defines=["-DPROBE_ZEPHYR", "-Wconversion"],
        includes=[learnbuild.RUNTIME_C, learnbuild.PROBES, capbot])
    status, stdout = qemu_harness.run_qemu(elf)
    assert status == 0, stdout
    cuts, rot = outcomes(stdout)
    check(cuts, ("zephyr",))
    assert rot == "old"
