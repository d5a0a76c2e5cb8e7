"""The learned-parameter store (runtime_c/swarmvm_store.c): a power cut at any point of a save
leaves the old record or the new one, never a mixture. The probe (c/store_probe.c) cuts the
medium's writes after k operations for every k across a whole save, with no, one and two
records saved before, on a simulated EEPROM and a simulated flash page (erase, then writes
that only clear bits) on the host, and on the ATmega328P's real EEPROM in simavr."""

import re

import pytest

import learnbuild

SOURCES = [learnbuild.RUNTIME_C / "swarmvm.c", learnbuild.RUNTIME_C / "swarmvm_store.c",
           learnbuild.PROBES / "store_probe.c"]
NEW_RECORD = 16           # bytes of the probe's record 3, saved under the cut
SAVE_OPERATIONS = 1 + 4 + 2 + NEW_RECORD + 2 + 1     # mark empty, sequence, length, payload, CRC, commit


def outcomes(text):
    """{(medium, prior records, k): outcome} and the bit-rot outcome from the probe's output."""
    cuts = {(medium, int(prior), int(k)): outcome
            for medium, prior, k, outcome in re.findall(r"cut (\w+) (\d+) (\d+) (\w+)", text)}
    assert "end" in text.split()
    return cuts, re.search(r"rot (\w+)", text).group(1)


def check(cuts, media):
    """Before the commit byte (the save's last operation) the load gives the record saved before
    (none when there was none), from it on the new one; every k up to past the save is there."""
    for medium in media:
        for prior in (0, 1, 2):
            for k in range(SAVE_OPERATIONS + 2):
                expected = "new" if k >= SAVE_OPERATIONS else "old" if prior else "none"
                assert cuts[(medium, prior, k)] == expected, (medium, prior, k)
    assert len(cuts) == len(media) * 3 * (SAVE_OPERATIONS + 2)


def test_a_cut_save_loads_the_old_or_the_new_record_on_the_host(tmp_path):
    exe = learnbuild.build_host(tmp_path / "store_probe", SOURCES, defines=())
    cuts, rot = outcomes(learnbuild.run_host(exe))
    check(cuts, ("eeprom", "flash"))
    assert rot == "old"


@pytest.mark.emulator
def test_a_cut_save_loads_the_old_or_the_new_record_on_the_avr_eeprom(tmp_path):
    elf = learnbuild.build_avr(tmp_path / "store_probe.elf", SOURCES)
    cuts, rot = outcomes(learnbuild.run_simavr(elf))
    check(cuts, ("eeprom",))
    assert rot == "old"
