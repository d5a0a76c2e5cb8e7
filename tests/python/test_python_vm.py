"""The Python VM's semantics, one rule at a time, on small supervisors written for the purpose."""

from pathlib import Path

import pytest

from conformance.cases import HOOKED, SWAP_FIRST, SWAP_SECOND
from swarmvm.compiler.pipeline import compile_inputs

CORPUS = Path(__file__).parent.parent / "corpus"


def image_of(tmp_path, text, name="m.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return compile_inputs([str(path)]).image


# One supervisor: controllable go (0 -> 1), uncontrollable back (1 -> 0) and tick (self-loops);
# public uncontrollable zmsg (self-loops). Events sorted: back, go, tick, zmsg.
LOOP = """num_events: 4
num_supervisors: 1
events: [ EV_go, EV_back, EV_tick, EV_zmsg ]
ev_controllable: [ 1, 0, 0, 0 ]
ev_public: [ 0, 0, 0, 1 ]
sup_events: [ [ 1, 1, 1, 1 ] ]
sup_init_state: [ 0 ]
sup_data_pos: [ 0 ]
sup_data: [ 3, EV_go, 0, 1, EV_tick, 0, 0, EV_zmsg, 0, 0, 3, EV_back, 0, 0, EV_tick, 0, 1, EV_zmsg, 0, 1 ]
"""


def test_generator_test_vectors(vm):
    r = vm.XorShift32(1)
    assert [r.next() for _ in range(4)] == [270369, 67634689, 2647435461, 307599695]
    r = vm.XorShift32(0)
    assert [r.next() for _ in range(2)] == [0x510C4619, 0xE02E553E]
    r = vm.XorShift32(42)
    assert [r.below(5) for _ in range(10)] == [0, 3, 0, 4, 4, 1, 4, 2, 3, 1]


def test_level_inputs_fire_every_step_edge_inputs_once(vm, tmp_path):
    image = image_of(tmp_path, LOOP)
    # tick's check is always true; back's is true at step 3 only (then go is enabled again).
    for mode, expected in (("level", [[2, 1], [2], [0, 2, 1], [2]]), ("edge", [[2, 1], [], [0, 1], []])):
        machine = vm.VM(image, inputs=mode, control="after-inputs")
        steps = iter([False, False, True, False])
        machine.bind("EV_tick", check=lambda _d: True)
        machine.bind("EV_back", check=lambda _d: next(steps))
        assert [machine.step() for _ in range(4)] == expected, mode


def test_if_quiet_holds_the_controllable_event_while_inputs_occur(vm, tmp_path):
    image = image_of(tmp_path, LOOP)
    machine = vm.VM(image, control="if-quiet")
    ticks = iter([True, True, False])
    machine.bind("tick", check=lambda _d: next(ticks))
    assert [machine.step() for _ in range(3)] == [[2], [2], [1]]


def test_public_events_are_applied_before_private_ones(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, LOOP), control="if-quiet")
    order = []
    for name in ("tick", "zmsg"):
        machine.bind(name, action=lambda _d, name=name: order.append(name), check=lambda _d: True)
    assert machine.step() == [3, 2]
    assert order == ["zmsg", "tick"]


def test_violations_are_counted_and_reported(vm, tmp_path):
    seen = []
    machine = vm.VM(image_of(tmp_path, LOOP), control="if-quiet", on_violation=lambda e, s: seen.append((e, s)))
    machine.bind("back", check=lambda _d: True)   # back is impossible in state 0
    assert machine.step() == [0]
    assert machine.states == [0] and machine.violations == 1 and seen == [(0, 0)]


TWO = """num_events: 2
num_supervisors: 1
events: [ EV_a, EV_b ]
ev_controllable: [ 1, 1 ]
sup_events: [ [ 1, 1 ] ]
sup_init_state: [ 0 ]
sup_data_pos: [ 0 ]
sup_data: [ 2, EV_a, 0, 0, EV_b, 0, 0 ]
sup_data_prob_pos: [ 0 ]
sup_data_prob: [ 2, 0.0, 1.0 ]
"""


def test_policy_first_follows_the_priority_list(vm, tmp_path):
    image = image_of(tmp_path, TWO.replace("sup_data_prob_pos: [ 0 ]\nsup_data_prob: [ 2, 0.0, 1.0 ]\n", ""))
    machine = vm.VM(image, policy="first")
    assert [machine.step() for _ in range(3)] == [[0], [0], [0]]
    machine = vm.VM(image, policy="first", priority=["EV_b"])
    assert [machine.step() for _ in range(3)] == [[1], [1], [1]]


def test_weighted_policy_never_picks_a_zero_weight_event(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, TWO), policy="weighted", seed=5)
    assert {machine.step()[0] for _ in range(200)} == {1}


def test_binding_an_unknown_name_is_an_error_not_event_0(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, LOOP))
    with pytest.raises(KeyError, match="EV_nope"):
        machine.bind("EV_nope", action=print)
    with pytest.raises(ValueError, match="controllable"):
        machine.bind("go", check=lambda _d: True)


def test_controller_methods_bind_by_name_and_unbound_checks_are_listed(vm, tmp_path):
    calls = []

    class Controller:
        def check_tick(self, data):
            return True

        def on_go(self, data):
            calls.append("go")

    machine = vm.VM(image_of(tmp_path, LOOP))
    assert machine.unbound_checks() == ["EV_zmsg", "EV_back", "EV_tick"]
    machine.bind_controller(Controller())
    assert machine.unbound_checks() == ["EV_zmsg", "EV_back"]
    assert machine.step() == [2, 1] and calls == ["go"]


def test_swap_rebinds_by_name_and_a_missing_name_keeps_the_old_logic(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, LOOP))
    machine.bind("tick", check=lambda _d: True)
    machine.step()
    assert machine.states == [1]
    renamed = image_of(tmp_path, LOOP.replace("EV_go", "EV_aa_go"), "n.yaml")   # go is now event 0
    machine.load(renamed)
    assert machine.states == [0] and machine.step() == [2, 0]
    with pytest.raises(KeyError):
        machine.load(image_of(tmp_path, LOOP.replace("EV_tick", "EV_tock"), "o.yaml"))
    assert machine.image.names[0] == "aa_go"


def test_reset_restores_states_counters_and_generator(vm):
    image = compile_inputs([str(CORPUS / "openswarm" / "network_leader.yaml")]).image
    machine = vm.VM(image, seed=9)
    first = [machine.step() for _ in range(20)]
    machine.reset()
    assert [machine.step() for _ in range(20)] == first


def test_nadzoru_compatible_api_runs_a_published_style_controller(vm, tmp_path):
    from click.testing import CliRunner
    from swarmvm.cli.commands import main
    yaml_path = tmp_path / "supervisor.yaml"
    yaml_path.write_text((CORPUS / "openswarm" / "capbot_demo.yaml").read_text())
    assert CliRunner().invoke(main, ["pack", str(yaml_path), "-o", str(tmp_path / "supervisor.svm")]).exit_code == 0
    log = []
    sct = vm.SCT(str(yaml_path))
    button = {"pressed": True}
    sct.add_callback(sct.EV["EV_btnMove"], lambda d: log.append("btnMove"), lambda d: d["pressed"], button)
    sct.add_callback(sct.EV["EV_move"], lambda d: log.append("move"), None, None)
    ev, controllable = sct.get_events()
    assert set(ev) == {"EV_move", "EV_btnStop", "EV_stop", "EV_btnMove"} and sum(controllable) == 2
    sct.run_step()
    assert log[0] == "btnMove" and sct.sup_current_state != [0]


def test_strict_mode_refuses_to_step_and_lists_every_unbound_check(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, LOOP), strict=True)
    machine.bind("tick", check=lambda _d: False)
    with pytest.raises(vm.UnboundEvents) as refused:
        machine.step()
    assert refused.value.names == ["EV_zmsg", "EV_back"]
    machine.bind("zmsg", check=lambda _d: False)
    machine.bind("back", check=lambda _d: False)
    assert machine.step() == [1]


def test_a_new_image_needing_an_event_the_application_lacks_is_reported_before_activation(vm, tmp_path):
    machine = vm.VM(image_of(tmp_path, LOOP))
    for name in ("tick", "zmsg", "back"):
        machine.bind(name, check=lambda _d: False)
    extra = LOOP.replace("num_events: 4", "num_events: 5").replace("EV_zmsg ]", "EV_zmsg, EV_alarm ]").replace(
        "[ 1, 0, 0, 0 ]", "[ 1, 0, 0, 0, 0 ]").replace("[ 0, 0, 0, 1 ]", "[ 0, 0, 0, 1, 0 ]").replace(
        "[ [ 1, 1, 1, 1 ] ]", "[ [ 1, 1, 1, 1, 0 ] ]")
    assert machine.load(image_of(tmp_path, extra, "x.yaml")) == ["EV_alarm"]
    strict = vm.VM(image_of(tmp_path, LOOP), strict=True)
    for name in ("tick", "zmsg", "back"):
        strict.bind(name, check=lambda _d: False)
    before = strict.image
    with pytest.raises(vm.UnboundEvents):
        strict.load(image_of(tmp_path, extra, "y.yaml"))
    assert strict.image is before and strict.step() == [1]


# LOOP's supervisor beside a second one over go and tick that allows go only after a tick
# (state 0: tick -> 1; state 1: go -> 1, tick -> 0).
LOOP_AND_GATE = LOOP.replace("num_supervisors: 1", "num_supervisors: 2").replace(
    "sup_events: [ [ 1, 1, 1, 1 ] ]", "sup_events: [ [ 1, 1, 1, 1 ], [ 1, 0, 1, 0 ] ]").replace(
    "sup_init_state: [ 0 ]", "sup_init_state: [ 0, 0 ]").replace("sup_data_pos: [ 0 ]", "sup_data_pos: [ 0, 20 ]").replace(
    "EV_zmsg, 0, 1 ]", "EV_zmsg, 0, 1, 1, EV_tick, 0, 1, 2, EV_go, 0, 1, EV_tick, 0, 0 ]")


def scripted_checks(machine, step):
    """Binds tick and back to checks that are true on a fixed pattern of the step number."""
    machine.bind("tick", check=lambda _d: step[0] % 3 == 0)
    machine.bind("back", check=lambda _d: step[0] % 4 == 1)


@pytest.mark.parametrize("model", [LOOP, LOOP_AND_GATE], ids=["one supervisor", "two supervisors"])
def test_an_action_that_rebinds_during_the_inputs_leaves_the_run_unchanged(vm, tmp_path, model):
    """An input's action that binds again makes a new plan mid-step; the step finishes out of
    line (VM._choose) with the same choices and the same generator draws as a run without it."""
    image = image_of(tmp_path, model)
    plain, rebinding = vm.VM(image, seed=3), vm.VM(image, seed=3)
    step = [0]
    scripted_checks(plain, step)
    scripted_checks(rebinding, step)
    rebinding.bind("tick", action=lambda _d: scripted_checks(rebinding, step))
    runs = {id(plain): [], id(rebinding): []}
    for machine in (plain, rebinding):
        for step[0] in range(60):
            runs[id(machine)].append((machine.step(), list(machine.states), machine.violations))
    assert runs[id(plain)] == runs[id(rebinding)]
    assert any(2 in fired for fired, _, _ in runs[id(plain)])     # tick fired: the action ran


def swap_images(tmp_path):
    """The images of conformance.cases' SWAP_FIRST and SWAP_SECOND."""
    return image_of(tmp_path, SWAP_FIRST, "first.yaml"), image_of(tmp_path, SWAP_SECOND, "second.yaml")


def test_an_action_that_loads_an_image_ends_the_step(vm, tmp_path):
    """x's action loads the second image while y fires too: the step ends after x (y was
    polled for the first image, whose index 3 the second does not have; no choice follows), and
    from then on the VM runs as a new VM of the second image (states, generator, violations)."""
    first, second = swap_images(tmp_path)
    machine, fresh = vm.VM(first, seed=7), vm.VM(second, seed=7)
    loaded: list = []
    machine.bind("x", check=lambda _d: True, action=lambda _d: loaded or loaded.append(machine.load(second)))
    fresh.bind("x", check=lambda _d: True)
    for m in (machine, fresh):
        m.bind("y", check=lambda _d: True)
    assert machine.step() == [2] and machine.states == [0] and machine.violations == 0
    runs = [[(m.step(), list(m.states), m.violations) for _ in range(10)] for m in (machine, fresh)]
    assert runs[0] == runs[1] and runs[0][0] == ([1, 2, 0], [1], 1)


def test_an_action_that_loads_an_image_ends_the_sct_exact_step(vm, tmp_path):
    """The same in SCT exact mode: the step's events are x's alone, in the file's numbering."""
    first, second = swap_images(tmp_path)
    path = tmp_path / "first.svm"
    path.write_bytes(compile_inputs([str(tmp_path / "first.yaml")]).ordered_image)
    sct = vm.SCT(str(path))
    sct.add_callback(sct.EV["EV_x"], lambda _d: sct.vm.load(second), lambda _d: True, None)
    sct.add_callback(sct.EV["EV_y"], None, lambda _d: True, None)
    sct.run_step()
    assert sct.last_events == sct.input_buffer == [sct.EV["EV_x"]] and sct.vm.image.num_events == 3


def test_a_violation_hook_that_raises_ends_the_step_there(vm, tmp_path):
    """As in C++ (tests/cpp/test_callback_errors_cpp.py, the same model): CallbackError names the
    hook; the supervisors after the violating one have not moved, the action has not run."""
    broken, acted = [True], []

    def hook(_event, _sup):
        if broken[0]:
            raise OSError("log full")
    machine = vm.VM(image_of(tmp_path, HOOKED), on_violation=hook)
    machine.bind("u", check=lambda _d: True, action=lambda _d: acted.append("u"))
    with pytest.raises(vm.CallbackError, match="the violation hook of EV_u raised OSError: log full") as caught:
        machine.step()
    assert (caught.value.event, caught.value.kind) == ("EV_u", "violation hook")
    assert isinstance(caught.value.__cause__, OSError)
    assert machine.states == [0, 0] and machine.violations == 1 and acted == []
    broken[0] = False
    assert len(machine.step()) == 2 and machine.states == [0, 1] and acted == ["u"]


def test_the_violation_hook_may_not_load_an_image(vm, tmp_path):
    """on_violation runs while the event's other supervisors are still to move: a load there is
    refused (as in C++), and the VM keeps its image; between steps the load is taken."""
    first, second = swap_images(tmp_path)
    machine = vm.VM(second, on_violation=lambda _event, _sup: machine.load(first))
    machine.bind("y", check=lambda _d: True)       # no move in the initial state
    with pytest.raises(RuntimeError, match="on_violation cannot load an image"):
        machine.step()
    assert machine.image.num_events == 3
    assert machine.load(first) == ["EV_x"] and machine.image.num_events == 4      # x has no check


def test_a_step_kept_across_a_bind_polls_the_new_checks(vm, tmp_path):
    """``step = vm.step`` kept by a caller, then a check bound again: the kept step hands over
    to the step written out for the new bindings, never polling the old check."""
    machine = vm.VM(image_of(tmp_path, LOOP), control="if-quiet")
    machine.bind("tick", check=lambda _d: False)
    machine.step()
    step = machine.step
    machine.bind("tick", check=lambda _d: True)
    assert step() == [2]
    assert step() == [2] and machine.step() == [2]
