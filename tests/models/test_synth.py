"""swarmvm synth: the energy worker's plants and specifications synthesise to the published
supervisors (by swarmvm equiv and by libFAUDES), every result is controllable and non-blocking
by libFAUDES' own checks, and the VM never fires a controllable event a synthesised
supervisor disables."""

import random

import faudes
import pytest

from models.model_cases import ENERGY_WORKER, SYNTHESIS, conjunction, run
from swarmvm.models.faudes_bridge import system_from_local
from swarmvm.readers.automata import load_automata
from swarmvm.compiler.pipeline import compile_inputs, compile_spec
from swarmvm.compiler.runtime_files import python_vm
from swarmvm.models.synthesis import models_by_name, synthesise
from swarmvm.readers.synth_script import parse_synth_script

PLANTS = {1: ("G1", "G3"), 2: ("G1", "G3"), 3: ("G1", "G2"), 4: ("G1", "G2")}


def energy_worker(suffix="xml", script="script.txt"):
    models = sorted(SYNTHESIS.glob("[GE]?.%s" % suffix))
    text = (SYNTHESIS / script).read_text()
    return synthesise(parse_synth_script(script, text), models_by_name([str(p) for p in models]))


@pytest.mark.parametrize("suffix,script", [("xml", "script.txt"), ("nza", "script.lua")])
def test_energy_worker_models_synthesise_to_the_published_supervisor(tmp_path, suffix, script):
    out = tmp_path / "synthesised.yaml"
    models = sorted(SYNTHESIS.glob("[GE]?.%s" % suffix))
    result = run("synth", "--script", SYNTHESIS / script, *models, "-o", out)
    assert result.exit_code == 0, result.stderr
    verdict = run("equiv", out, ENERGY_WORKER)
    assert verdict.exit_code == 0 and verdict.stdout.startswith("equivalent")
    ours, published = compile_inputs([str(out)]).model, compile_inputs([str(ENERGY_WORKER)]).model
    assert faudes.LanguageEquality(conjunction(ours), conjunction(published))
    assert ours.events == published.events and ours.controllable == published.controllable


def test_synthesis_as_options_equals_the_script_and_minimising_keeps_the_language(tmp_path):
    statements = []
    for i, plants in PLANTS.items():
        statements += ["-e", "Gloc%d = Sync(%s)" % (i, ", ".join(plants)), "-e", "Kloc%d = Sync(Gloc%d, E%d)" % (i, i, i),
                       "-e", "Sloc%d = SupC(Gloc%d, Kloc%d)" % (i, i, i)]
    out = tmp_path / "options.yaml"
    result = run("synth", *statements, "--minimise", *sorted(SYNTHESIS.glob("[GE]?.xml")), "-o", out)
    assert result.exit_code == 0, result.stderr
    assert run("equiv", out, ENERGY_WORKER).exit_code == 0


def test_every_synthesised_supervisor_is_controllable_and_nonblocking_by_libfaudes():
    spec = energy_worker()
    inputs = load_automata([str(SYNTHESIS / ("%s.xml" % n)) for n in ("G1", "G2", "G3")])
    plants = {name: system_from_local(local, inputs.controllable) for name, local in zip(("G1", "G2", "G3"), inputs.supervisors)}
    assert len(spec.supervisors) == 4
    for i, local in enumerate(spec.supervisors, 1):
        supervisor = system_from_local(local, spec.controllable)
        plant = faudes.Parallel(*(plants[p] for p in PLANTS[i]))
        assert faudes.IsControllable(plant, supervisor.ControllableEvents(), supervisor)
        assert faudes.IsNonblocking(supervisor)
        assert local.marked        # the marking libFAUDES computed is kept


def test_the_vm_never_fires_a_controllable_event_a_synthesised_supervisor_disables():
    spec = energy_worker()
    vm_module = python_vm()
    compiled = compile_spec(spec, ["energy_worker"])
    image = vm_module.Image.parse(compiled.image)
    names = compiled.model.events
    fired_controllable = set()
    for seed in range(20):
        rng = random.Random(seed)
        machine = vm_module.VM(image, seed=seed + 1)
        row = {"now": set()}
        for event in machine.input_order:
            machine.bind(event, check=lambda _d, event=event: event in row["now"])
        machine.reset()
        states = [local.initial for local in spec.supervisors]
        for _ in range(60):
            row["now"] = {e for e in machine.input_order if rng.random() < 0.3}
            for event in machine.step():
                name = names[event]
                for s, local in enumerate(spec.supervisors):
                    if name not in local.alphabet:
                        continue
                    target = next((t.target for t in local.states[states[s]] if t.event == name), None)
                    if compiled.model.controllable[event]:
                        assert target is not None, "EV_%s fired while supervisor %d disables it" % (name, s)
                        fired_controllable.add(name)
                    states[s] = states[s] if target is None else target
    assert fired_controllable == {"moveToWork", "work", "moveToCharge", "charge"}


def test_a_plant_is_extended_by_the_specification_events_it_lacks(write_gen, tmp_path):
    # The plant knows only a (controllable); the specification allows c (controllable) once
    # after a. libFAUDES needs equal alphabets: the plant gets c as a self-loop.
    plant = write_gen("G", ["p0 a p0"], controllable=("a",), initial="p0")
    spec = write_gen("E", ["k0 a k1", "k1 c k2", "k2 a k2"], controllable=("a", "c"), initial="k0")
    out = tmp_path / "s.yaml"
    result = run("synth", "-e", "S = SupC(G, E)", plant, spec, "-o", out)
    assert result.exit_code == 0, result.stderr
    model = compile_inputs([str(out)]).model
    assert model.events == ("a", "c") and model.controllable == (True, True)
    reference = write_gen("R", ["r0 a r1", "r1 c r2", "r2 a r2"], controllable=("a", "c"), initial="r0")
    assert run("equiv", out, reference).exit_code == 0


def test_an_uncontrollable_event_the_specification_forbids_empties_the_supervisor(write_gen, tmp_path):
    plant = write_gen("G", ["p0 u p0"], initial="p0")
    spec = write_gen("E", ["k0 u k1"], initial="k0", marked=["k0", "k1"])
    result = run("synth", "-e", "S = SupC(G, E)", plant, spec, "-o", tmp_path / "s.yaml")
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: --statement: S: line 1: the result is empty (no supervisor exists)\n"
    assert not (tmp_path / "s.yaml").exists()


@pytest.mark.parametrize("script,message", [
    ("S = SupC(G)", "SupC: line 1: takes 2 argument(s), got 1"),
    ("S = Frobnicate(G, E)", "Frobnicate: line 1: unknown operation (expected Sync, SupC or Minimize)"),
    ("S = SupC(G, X)", "X: line 1: neither a model given nor assigned above"),
    ("S = __import__('os').system('true')", "__import__: line 1: unknown operation (expected Sync, SupC or Minimize)"),
    ("os.system('true')", "script: line 1: not a statement: \"os.system('true')\" (expected NAME = Op(ARGS) or export(NAMES))"),
    ("S = SupC(G, E)\nexport(T)", "export: T is not a model or a result of the script"),
])
def test_bad_scripts_get_one_line(write_gen, tmp_path, script, message):
    models = [write_gen("G", ["p0 a p0"], controllable=("a",), initial="p0"),
              write_gen("E", ["k0 a k0"], controllable=("a",), initial="k0")]
    (tmp_path / "s.txt").write_text(script + "\n")
    result = run("synth", "--script", tmp_path / "s.txt", *models, "-o", tmp_path / "out.yaml")
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: %s\n" % (tmp_path / "s.txt", message)


def test_script_comments_prints_and_exports_are_read_as_data():
    script = parse_synth_script("s.lua", '-- comment\nA = sync(G1, G2) # note\nprint("--- not a comment")\n'
                                         "B = supc(A, A)\nB = minimize(B)\nexport( B )\n")
    assert [(s.target, s.op, s.args) for s in script.steps] == [
        ("A", "sync", ("G1", "G2")), ("B", "supc", ("A", "A")), ("B", "min", ("B",))]
    assert script.exports == ("B",)


def test_a_compiled_supervisor_is_not_a_model(tmp_path):
    result = run("synth", "-e", "S = SupC(energy_worker, energy_worker)", ENERGY_WORKER, "-o", tmp_path / "s.yaml")
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: not an automaton file (.xml, .xmd, .nza, .gen)\n" % ENERGY_WORKER
