"""The generated Kilobot Makefile, run by real make with avr-gcc against the real kilolib
(issue 27): it rebuilds when its flags change (`make STREAM=1` after `make` said the image was up
to date and kept the other one), says what KILOLIB is when it is not given (it said `No rule to
make target '../kilolib/build/kilolib.a'`), and `make LEARNED=1` builds exactly the models
docs/robots/kilobot.md says fit: states x controllable events of at most 94 parameters."""

import subprocess
from pathlib import Path

import pytest

from checkout import EXAMPLE, ROOT
from targets.kilobot.needs import kilolib_or_skip
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import generate

FORAGER = ROOT / "examples" / "learning" / "supervisor.yaml"     # 5 states x 6 controllable events
LARGEST_LEARNED = 94        # docs/robots/kilobot.md: parameters that fit the EEPROM's two slots


def gen(model: Path, out: Path, name: str) -> Path:
    write_outputs(out, generate(compile_inputs([str(model)], name=name), "kilobot"))
    return out


def make(folder: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["make", *args], cwd=folder, capture_output=True, text=True)


def ring(path: Path, states: int, events: int, uncontrollable: int = 0) -> Path:
    """A one-supervisor model of ``states`` states in a ring, each with a transition on each of
    ``events`` controllable and ``uncontrollable`` other events: its learned policy has states x
    events parameters (the uncontrollable events need none)."""
    names = ["EV_e%d" % e for e in range(events + uncontrollable)]
    data = []
    for state in range(states):
        after = (state + 1) % states
        data += [str(len(names))] + [part for name in names for part in (name, str(after >> 8), str(after & 255))]
    path.write_text("num_events: %d\nnum_supervisors: 1\nevents: [ %s ]\nev_controllable: [ %s ]\n"
                    "sup_events: [ [%s] ]\nsup_init_state: [ 0 ]\nsup_current_state: [ 0 ]\nsup_data_pos: [ 0 ]\n"
                    "sup_data: [ %s ]\n" % (len(names), ", ".join(names), ", ".join(["1"] * events + ["0"] * uncontrollable),
                                            ", ".join(["1"] * len(names)), ", ".join(data)))
    return path


@pytest.fixture(scope="module")
def kilolib():
    return "KILOLIB=%s" % kilolib_or_skip()


def test_without_kilolib_the_makefile_says_what_it_is(tmp_path):
    out = gen(EXAMPLE, tmp_path, "worker")
    result = make(out)
    assert result.returncode != 0 and "No rule to make target" not in result.stderr
    assert "KILOLIB=../kilolib holds no build/kilolib.a: KILOLIB is the kilolib folder" in result.stderr
    assert "make KILOLIB=/path/to/kilolib" in result.stderr
    assert make(out, "clean").returncode == 0          # clean needs no kilolib


def test_a_changed_flag_rebuilds_the_image(tmp_path, kilolib):
    out = gen(EXAMPLE, tmp_path, "worker")
    assert make(out, "-s", kilolib).returncode == 0
    plain = (out / "worker.hex").read_bytes()
    assert "up to date" in make(out, kilolib).stdout
    stream = make(out, kilolib, "STREAM=1")
    assert stream.returncode == 0 and "swarmvm_stream.c" in stream.stdout, stream.stdout + stream.stderr
    assert (out / "worker.hex").read_bytes() != plain
    assert "up to date" in make(out, kilolib, "STREAM=1").stdout
    back = make(out, kilolib)
    assert back.returncode == 0 and "avr-gcc" in back.stdout
    assert (out / "worker.hex").read_bytes() == plain


@pytest.mark.parametrize("model,fits", [("forager", True), ("energy_worker", False),
                                        ("ring_47x2", True), ("ring_19x5", False), ("ring_20x4+2", True)])
def test_learned_builds_the_models_the_robot_page_says_fit(model, fits, tmp_path, kilolib):
    if model == "forager":
        source = FORAGER
    elif model == "energy_worker":
        source = EXAMPLE                                # 32 states x 4 controllable events: 128
    else:
        # 20x4+2: 20 states, 4 controllable and 2 uncontrollable events, 80 parameters (the
        # Makefile reserved 20 x 6 = 120, all events, and the build stopped)
        states, events = map(int, model.split("_")[1].split("+")[0].split("x"))
        assert (states * events <= LARGEST_LEARNED) == fits
        source = ring(tmp_path / "ring.yaml", states, events, int(model.partition("+")[2] or 0))
    out = gen(source, tmp_path / "app", "app")
    result = make(out, "-s", kilolib, "LEARNED=1", "app.elf")
    if fits:
        assert result.returncode == 0, result.stderr
    else:
        assert result.returncode != 0
        assert "the learned parameters' two slots do not fit the EEPROM" in result.stderr
