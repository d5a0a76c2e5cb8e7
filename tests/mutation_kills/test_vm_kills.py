"""The Python VM (runtime_py/swarmvm_vm.py) pinned where `make mutation` found it unpinned (issue
29, docs/mutation.md): the weighted policy over events that all weigh 0, the cache of written-out
steps (bounded, a hit returns the same maker, evicted sources leave linecache), the file name a
traceback through a step shows, the violation counter's stop, binding by index at its bounds and
a controller's checks bound on uncontrollable events only, and the refusal of an unknown policy."""

import linecache
import random
import re
import struct
import subprocess
import sys
import traceback

import pytest

from conformance.cases import compiled_image, supervisor_yaml
from one_state_image import one_state_image
from swarmvm.compiler.runtime_files import RUNTIME_PY_DIR, image_format, step_source

F = image_format()


def two_choices(probs):
    """One supervisor of one state, controllable events 0 and 1 looping on it, with Q15
    probabilities ``probs``."""
    return one_state_image(2, 0b11, probs=probs)


def test_the_weighted_policy_draws_uniformly_when_every_enabled_event_weighs_0(vm):
    weighted = vm.VM(two_choices([0, 0]), policy="weighted", seed=7)
    uniform = vm.VM(two_choices([0, 0]), policy="uniform", seed=7)
    runs = [weighted.step() for _ in range(40)]
    assert runs == [uniform.step() for _ in range(40)]
    assert {tuple(run) for run in runs} == {(0,), (1,)}


def test_the_cache_of_written_out_steps_holds_64_and_is_emptied_by_the_65th(monkeypatch):
    steps = step_source()
    monkeypatch.setattr(steps, "COMPILED", {})
    first = steps.compiled(("probe", 0), ["a"], ["return a"])
    for n in range(1, 64):
        steps.compiled(("probe", n), ["a"], ["return a + %d" % n])
    assert steps.compiled(("probe", 0), ["a"], ["return a"]) is first and len(steps.COMPILED) == 64
    steps.compiled(("probe", 64), ["a"], ["return a + 64"])
    assert list(steps.COMPILED) == [("probe", 64)]


def test_a_written_out_step_is_compiled_once_per_key_and_the_cache_stays_bounded(monkeypatch):
    steps = step_source()
    monkeypatch.setattr(steps, "COMPILED", {})
    first = steps.compiled(("probe", 0), ["a"], ["return a"])
    steps.compiled(("probe", 1), ["a"], ["return a + 1"])
    assert steps.compiled(("probe", 0), ["a"], ["return a"]) is first
    for n in range(2, steps.MAX_COMPILED + 5):
        steps.compiled(("probe", n), ["a"], ["return a + %d" % n])
        assert len(steps.COMPILED) <= steps.MAX_COMPILED
    assert first.__code__.co_filename not in linecache.cache                 # evicted with its source lines
    assert steps.compiled(("probe", 0), ["a"], ["return a"]) is not first     # evicted, compiled anew


def test_a_traceback_through_a_written_out_step_names_its_kind_and_shows_its_lines(vm):
    machine = vm.VM(two_choices([F.Q15_ONE, F.Q15_ONE]))
    machine.bind(0, action=lambda data: 1 / 0)
    with pytest.raises(vm.CallbackError) as raised:
        machine.step()
    frames = [frame for frame in traceback.extract_tb(raised.value.__traceback__)
              if frame.filename.startswith("<swarmvm ")]
    assert frames and all(re.fullmatch(r"<swarmvm canonical step [0-9a-f]{12}>", frame.filename) and frame.line
                          for frame in frames)
    # linecache holds the step's lines as it holds a file's: each with its line end
    assert all(linecache.getline(frame.filename, frame.lineno).endswith("\n") for frame in frames)


@pytest.mark.parametrize("option,message", [
    ({"policy": "best"}, "policy must be one of ('uniform', 'first', 'weighted', 'learned')"),
    ({"control": "never"}, "control must be one of ('after-inputs', 'if-quiet')"),
    ({"inputs": "pulse"}, "inputs must be one of ('level', 'edge')"),
])
def test_an_unknown_option_is_refused_naming_the_choices(vm, option, message):
    with pytest.raises(ValueError) as refused:
        vm.VM(two_choices([0, 0]), **option)
    assert str(refused.value) == message


def test_a_vm_is_seeded_1_by_default(vm):
    machine, oracle = vm.VM(two_choices([0, 0])), vm.XorShift32(1)
    assert [machine.step() for _ in range(24)] == [[oracle.below(2)] for _ in range(24)]


def test_policy_first_ranks_the_listed_events_then_the_others_by_name(vm, tmp_path):
    """Events a, b, c (by name), b listed: b first, then a, then c."""
    image = compiled_image(tmp_path, supervisor_yaml(["a", "b", "c"], [1, 1, 1], [{"a", "b", "c"}],
                                               [[[("a", 0), ("b", 0), ("c", 0)]]]))
    rank = vm.VM(image, policy="first", priority=["b"]).rank
    assert sorted(range(3), key=rank.__getitem__) == [1, 0, 2]


def test_the_default_generator_starts_from_seed_1(vm):
    """xorshift32 (13, 17, 5) from 1: 1 ^ 1 << 13 = 8193, then 8193 ^ 8193 << 5 = 270369."""
    rng = vm.XorShift32()
    assert (rng.state, rng.next()) == (1, 270369)
    assert vm.XorShift32(0).state == 0x9E3779B9 and vm.XorShift32(2 ** 32 + 5).state == 5


def test_the_weighted_draw_takes_the_first_event_below_its_weight_and_the_next_at_it(vm):
    """Weights 1 and 1 (Q15): a draw of 0 picks event 0, a draw of 1 (equal to its weight) event 1."""
    machine = vm.VM(two_choices([1, 1]), policy="weighted", seed=3)
    oracle = vm.XorShift32(3)
    choices = [machine.step() for _ in range(32)]
    assert choices == [[0] if oracle.next() % 2 < 1 else [1] for _ in range(32)]
    assert [0] in choices and [1] in choices


# Controllable "go" (event 0 in name order) and uncontrollable "hit" (event 1): hit leads from
# state 0 to state 1, where neither is defined; go loops on state 0.
HIT_ONCE = supervisor_yaml(["hit", "go"], [0, 1], [{"hit", "go"}], [[[("hit", 1), ("go", 0)], []]])


def test_the_violation_counter_stops_at_its_maximum(vm, tmp_path):
    machine = vm.VM(compiled_image(tmp_path, HIT_ONCE))
    machine.bind("hit", check=lambda data: True)
    machine.step()
    machine.violations = vm.MAX_VIOLATIONS - 2
    machine.step()
    assert machine.violations == vm.MAX_VIOLATIONS - 1
    machine.step()
    machine.step()
    assert machine.violations == vm.MAX_VIOLATIONS == 0xFFFFFFFF


def test_an_event_index_is_bound_from_0_to_the_last_event(vm, tmp_path):
    machine = vm.VM(compiled_image(tmp_path, HIT_ONCE))
    machine.bind(1, check=lambda data: False)
    assert sorted(machine.checks) == [1]
    for index in (2, -1):
        with pytest.raises(KeyError) as refused:
            machine.bind(index, action=print)
        assert refused.value.args[0] == "event index %d out of range (0..1)" % index


def test_a_controller_s_checks_are_bound_on_its_uncontrollable_events_only(vm, tmp_path):
    class Controller:
        def on_go(self, data):
            pass

        def check_go(self, data):
            return True

        def check_hit(self, data):
            return True

    machine = vm.VM(compiled_image(tmp_path, HIT_ONCE))
    machine.bind_controller(Controller())
    assert sorted(machine.checks) == [1] and sorted(machine.actions) == [0]

    class Other:                # the controllable event second: "aa" an input, "zz" controllable
        def check_aa(self, data):
            return True

        def check_zz(self, data):
            return True

    machine = vm.VM(compiled_image(tmp_path, supervisor_yaml(["aa", "zz"], [0, 1], [{"aa", "zz"}],
                                                       [[[("aa", 0), ("zz", 0)]]])))
    machine.bind_controller(Other())
    assert sorted(machine.checks) == [0]


# Uncontrollable "hit" and controllable "a" and "b", all self-loops on one state (file order).
THREE_LOOPS = supervisor_yaml(["hit", "a", "b"], [0, 1, 1], [{"hit", "a", "b"}],
                              [[[("hit", 0), ("a", 0), ("b", 0)]]])


def sct_of(vm, tmp_path, **options):
    path = tmp_path / "s.yaml"
    path.write_text(THREE_LOOPS)
    return vm.SCT(str(path), **options)


def test_the_canonical_sct_step_buffers_the_inputs_without_the_controllable_event(vm, tmp_path):
    """Two inputs and a controllable event fire: the buffer holds both inputs."""
    path = tmp_path / "two.yaml"
    path.write_text(supervisor_yaml(["hit", "kick", "go"], [0, 0, 1], [{"hit", "kick", "go"}],
                                    [[[("hit", 0), ("kick", 0), ("go", 0)]]]))
    sct = vm.SCT(str(path), exact=False)
    for name in ("EV_hit", "EV_kick"):
        sct.add_callback(sct.EV[name], None, lambda data: True, None)
    sct.run_step()
    assert len(sct.last_events) == 3 and sorted(sct.input_buffer) == sorted([sct.EV["EV_hit"], sct.EV["EV_kick"]])
    assert sct.ev_controllable[sct.last_events[-1]] == 1


def test_an_exact_sct_check_that_raises_reaches_the_caller_as_it_is(vm, tmp_path):
    """As the published VM: no CallbackError around it."""
    sct = sct_of(vm, tmp_path)
    sct.add_callback(sct.EV["EV_hit"], None, lambda data: 1 / 0, None)
    with pytest.raises(ZeroDivisionError):
        sct.run_step()


def test_a_step_whose_input_action_registers_again_chooses_as_published(vm, tmp_path):
    """An input's action that calls add_callback replaces the VM's plan mid-step: the choice is
    then made out of line (SCT._choose), still the k-th enabled event in file order,
    k = randint(0, 10**9) % n."""
    sct = sct_of(vm, tmp_path)
    chosen = []

    def action(data):
        sct.add_callback(sct.EV["EV_a"], lambda data: None, None, None)

    sct.add_callback(sct.EV["EV_hit"], action, lambda data: True, None)
    random.seed(11)
    for _ in range(24):
        sct.run_step()
        chosen.append(sct.last_events[-1])
    random.seed(11)
    expected = [(sct.EV["EV_a"], sct.EV["EV_b"])[random.randint(0, 1000000000) % 2] for _ in range(24)]
    assert chosen == expected and set(chosen) == {sct.EV["EV_a"], sct.EV["EV_b"]}


def test_an_image_without_a_source_section_beside_its_yaml_is_read(vm, tmp_path):
    """Only an image that records its YAML's digest is compared with the file beside it."""
    (tmp_path / "s.yaml").write_text(THREE_LOOPS)
    raw = two_choices([0, 0])
    (tmp_path / "s.svm").write_bytes(raw)
    image = vm._image_beside(str(tmp_path / "s.yaml"))
    assert image.source is None and image.raw == raw


def test_a_strict_vm_refuses_to_step_before_every_input_has_a_check(vm, tmp_path):
    machine = vm.VM(compiled_image(tmp_path, HIT_ONCE), strict=True)
    with pytest.raises(vm.UnboundEvents) as refused:
        machine.step()
    assert str(refused.value) == "no check bound for EV_hit"
    machine.bind("hit", check=lambda data: False)
    assert machine.step() == [0]


def test_the_moves_table_gives_each_state_its_successors_by_event(vm, tmp_path):
    machine = vm.VM(compiled_image(tmp_path, HIT_ONCE))
    assert machine.moves == [[{0: 0, 1: 1}, {}]]


def test_the_vm_module_imports_beside_its_format_without_the_compiler(tmp_path):
    """A Pi-puck has runtime_py's three files and no swarmvm package: the VM imports the format
    and step-writer modules beside it (typing's branch is only mypy's)."""
    for name in ("swarmvm_vm.py", "swarmvm_format.py", "swarmvm_step_source.py"):
        (tmp_path / name).write_bytes((RUNTIME_PY_DIR / name).read_bytes())
    run = subprocess.run([sys.executable, "-I", "-c", "import sys; sys.path.insert(0, '.'); import swarmvm_vm; "
                          "print(swarmvm_vm.Image.__module__)"], cwd=tmp_path, capture_output=True, text=True)
    assert (run.returncode, run.stdout) == (0, "swarmvm_format\n"), run.stderr


def test_a_check_that_raises_is_named_by_its_event_when_it_is_the_only_input(vm, tmp_path):
    """The input "aa" is event 0 of 2 (not the last, whose name an index of -1 would give)."""
    machine = vm.VM(compiled_image(tmp_path, supervisor_yaml(["aa", "zz"], [0, 1], [{"aa", "zz"}],
                                                       [[[("aa", 0), ("zz", 0)]]])))
    machine.bind("aa", check=lambda data: 1 / 0)
    with pytest.raises(vm.CallbackError) as raised:
        machine.step()
    assert (raised.value.event, raised.value.kind) == ("EV_aa", "check")


def test_the_learned_policy_needs_a_learner_and_takes_one(vm, tmp_path):
    with pytest.raises(ValueError) as refused:
        vm.VM(two_choices([0, 0]), policy="learned")
    assert str(refused.value) == "policy 'learned' needs a learner"

    class First:
        def choose(self, machine, enabled):
            return enabled[-1]

    assert vm.VM(two_choices([0, 0]), policy="learned", learner=First()).step() == [1]


def test_callbacks_bound_by_name_refuse_an_image_without_names(vm, tmp_path):
    named = compiled_image(tmp_path, HIT_ONCE)
    nameless = F.Image.parse(two_choices([0, 0]))
    machine = vm.VM(named)
    machine.bind("go", action=print)
    with pytest.raises(KeyError) as refused:
        machine.load(nameless)
    assert refused.value.args[0] == "the new image carries no event names to rebind callbacks by"
    assert vm.VM(named).load(nameless) == []        # nothing bound: nothing to rebind


# Two supervisors sharing the controllable "go": each moves from its state 0 to its state 1.
SHARED = supervisor_yaml(["go"], [1], [{"go"}, {"go"}], [[[("go", 1)], []], [[("go", 1)], []]])


def test_an_event_fired_moves_every_supervisor_that_has_it(vm, tmp_path):
    machine = vm.VM(compiled_image(tmp_path, SHARED))
    machine._apply(0)
    assert machine.states == [1, 1]


def test_the_weighted_policy_reads_the_weights_of_the_state_the_supervisor_is_in(vm, tmp_path):
    """States 0 -a-> 1, 1 -b (weight 1)-> 2 and -c (weight 0)-> 2, 2 -d-> 0: c is never taken."""
    image = compiled_image(tmp_path, supervisor_yaml(["a", "b", "c", "d"], [1, 1, 1, 1], [{"a", "b", "c", "d"}],
                                               [[[("a", 1)], [("b", 2), ("c", 2)], [("d", 0)]]],
                                               probabilities=[[["1"], ["1", "0"], ["1"]]]))
    machine = vm.VM(image, policy="weighted", seed=5)
    assert [machine.step() for _ in range(30)] == [[0], [1], [3]] * 10


def test_an_image_whose_start_state_is_past_its_supervisor_is_refused(vm, tmp_path):
    """The source section's start state of a one-state supervisor: 0 is read, 1 refused."""
    for start in (0, 1):
        sections = {"controllable": b"\x03", "public": b"\0", "supervisors": b"\x03" + F.SUPERVISOR_RECORD.pack(0, 1, 0),
                    "states": b"\x03" + F.STATE_RECORD.pack(0), "targets": bytes(2), "names": b"\x01a\x01b",
                    "order": b"\x00\x01" + struct.pack("<H", 0),
                    "source": bytes(F.SOURCE_DIGEST_SIZE) + struct.pack("<H", start) + b"\x01a\x01b"}
        path = tmp_path / "s.svm"
        path.write_bytes(F.assemble(2, 1, 1, 2, 1, sections))
        if start == 0:
            assert vm.SCT(str(path)).vm.states == [0]
            continue
        with pytest.raises(F.ImageError) as refused:
            vm.SCT(str(path))
        assert str(refused.value) == "%s: image source section: a start state outside its supervisor" % path
