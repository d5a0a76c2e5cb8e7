"""Conformance of the C VM on the ATmega328P in simavr (-m atmega328p -f 8000000).

The same harness as the host suite, built with avr-gcc and the official Kilobot flags, image
and scripts in PROGMEM, output on USART0. Every run of every corpus batch must print the
reference trace. The loaded pass (image copied to RAM and swapped in) runs whenever the copy
fits the 2 KB of SRAM: with runtime bindings, or with compile-time dispatch when the binding
table does not fit as well (network_worker: its 1,693-byte image leaves no room for both). A
third pass runs the image from EEPROM (svm_load_E) when it fits the 1 KB EEPROM (all but
network_worker)."""

import pytest

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import SUPERVISORS, batch

pytestmark = pytest.mark.emulator   # runs simavr or QEMU


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_avr_trace_equals_reference(path, tmp_path):
    b = batch(path)
    eeprom = c_harness.fits_eeprom(b)
    elf, loaded = c_harness.build_avr(b, tmp_path, eeprom=eeprom)
    traces, info = c_harness.parse(c_harness.run_avr(elf))
    passes = (0,) + ((1,) if loaded else ()) + ((2,) if eeprom else ())
    assert mismatches(b, traces, info, passes) == []


def test_avr_loaded_passes_run_for_the_example(tmp_path):
    """The RAM-loaded (with runtime bindings) and EEPROM paths must really be exercised on AVR
    for the Kilobot example, not silently dropped."""
    b = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    assert c_harness.fits_eeprom(b)
    elf, loaded = c_harness.build_avr(b, tmp_path, eeprom=True)
    assert loaded == c_harness.LOADED_FULL
    traces, _ = c_harness.parse(c_harness.run_avr(elf))
    assert {p for p, _ in traces} == {0, 1, 2}


def test_avr_kilobot_build_flags_trace_equals_reference(tmp_path):
    """The configuration of a generated Kilobot image (image in flash only, exact mask width:
    templates/kilobot/Makefile.j2) prints the reference traces too."""
    b = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    elf, _ = c_harness.build_avr(b, tmp_path, extra=["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"],
                                 loaded_modes=(c_harness.LOADED_NONE,))
    traces, info = c_harness.parse(c_harness.run_avr(elf))
    assert mismatches(b, traces, info, passes=(0,)) == []
