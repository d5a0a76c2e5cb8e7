"""Conformance of the C VM on the ATmega328P in simavr (-m atmega328p -f 8000000).

The same harness as the host suite, built with avr-gcc and the official Kilobot flags, image
and scripts in PROGMEM, output on USART0. Every run of every corpus batch must print the
reference trace. The loaded pass (image copied to RAM and swapped in) runs whenever the copy
fits the 2 KB of SRAM: with runtime bindings, or with compile-time dispatch when the binding
table does not fit as well (network_worker: its 1,693-byte image leaves no room for both). A
third pass runs the image from EEPROM (svm_load_E) when it fits the 1 KB EEPROM (all but
network_worker). An image too large for a RAM copy runs from flash; a model too wide for the VM
on the AVR at all is refused in one line, by the build helper and by `make emulate`."""

import subprocess
import sys

import pytest

from checkout import FIRMWARE
from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.inspected import inspected_states, states_of
from conformance.cases import SUPERVISORS, Batch, Run, batch, supervisor_yaml
from conformance.test_widest_model import MODEL as WIDEST
from swarmvm.compiler.pipeline import compile_inputs

pytestmark = pytest.mark.emulator   # runs simavr or QEMU


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_avr_trace_equals_reference(path, tmp_path):
    b = batch(path)
    eeprom = c_harness.fits_eeprom(b)
    elf, loaded = c_harness.build_avr(b, tmp_path, eeprom=eeprom)
    traces, info = c_harness.parse(c_harness.run_avr(elf))
    passes = (0,) + ((1,) if loaded else ()) + ((2,) if eeprom else ())
    assert mismatches(b, traces, info, passes) == []
    runs = {"run%d" % run: lines for (step_pass, run), lines in traces.items() if step_pass == 0}
    assert inspected_states(path, runs, tmp_path) == states_of(runs)     # the inspector's page of the AVR's runs


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


def ring_yaml(states):
    """One supervisor: a ring of ``states`` states under one controllable event ``go`` and an
    uncontrollable self-loop ``tick``: an image of about 7 bytes a state."""
    ring = [[("go", (s + 1) % states), ("tick", s)] for s in range(states)]
    return supervisor_yaml(["go", "tick"], [1, 0], [{"go", "tick"}], [ring], public=[0, 0])


def test_an_image_over_the_ram_copy_runs_from_flash(tmp_path):
    """An image the 2 KB of RAM cannot hold a copy of (here 3 KB) is run with its tables in
    flash only, not refused: pass 0 only, every run the reference trace."""
    model = tmp_path / "ring.yaml"
    model.write_text(ring_yaml(400))
    b = batch(str(model))
    assert len(b.image) > 2048
    elf, loaded = c_harness.build_avr(b, tmp_path / "build")
    assert loaded == c_harness.LOADED_NONE
    traces, info = c_harness.parse(c_harness.run_avr(elf))
    assert mismatches(b, traces, info, passes=(0,)) == []


def test_a_model_too_wide_for_the_avr_is_refused_naming_the_limit(tmp_path):
    """At 255 events the step's stack frame alone is about 2 KB: the build helper says so in one
    line instead of a link error or a program that overruns its stack."""
    b = Batch("widest", "widest.yaml", compile_inputs([str(widest(tmp_path))]).image, ((frozenset(),),),
              (Run("level", "after-inputs", "uniform", 1, 0),))
    with pytest.raises(c_harness.AvrRamError) as refused:
        c_harness.build_avr(b, tmp_path / "build")
    assert str(refused.value).count("\n") == 0 and str(refused.value).startswith(
        "widest: 255 events, 1 supervisors, 1 states: the VM does not fit the ATmega328P's 2048 bytes of RAM")


def widest(tmp_path):
    model = tmp_path / "widest.yaml"
    model.write_text(WIDEST)
    return model


def emulate(model, tmp_path):
    return subprocess.run([sys.executable, str(FIRMWARE / "emulate_example.py"), str(model), "--build",
                           str(tmp_path / "emulate")], capture_output=True, text=True, timeout=600)


def test_emulate_runs_a_corpus_supervisor_other_than_the_example(tmp_path):
    result = emulate(next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml")), tmp_path)
    assert result.returncode == 0 and result.stderr == "", result.stdout + result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == 5 and all("identical to the Python VM" in line for line in lines[1:]), result.stdout


def test_emulate_says_in_one_line_that_a_wide_model_does_not_fit_the_avr(tmp_path):
    result = emulate(widest(tmp_path), tmp_path)
    assert result.returncode == 0 and result.stderr == "", result.stdout + result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == 5 and "not run: widest: 255 events" in lines[1] and "2048 bytes of RAM" in lines[1]
    assert all("identical to the Python VM" in line for line in lines[2:]), result.stdout
