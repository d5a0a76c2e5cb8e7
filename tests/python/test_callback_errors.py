"""A Python callback that raises (docs/semantics.md, "Callbacks that raise"): the caller gets
CallbackError naming the event and the kind of callback, with the original as its cause; a
raising check leaves the VM as it was before the step, a raising action leaves its own
transition applied; the next step runs normally."""

import random

import pytest

from checkout import EXAMPLE
from swarmvm.compiler.pipeline import compile_inputs


@pytest.fixture
def image():
    return compile_inputs([str(EXAMPLE)]).image


def test_a_raising_check_abandons_the_step_before_any_transition(vm, image):
    machine = vm.VM(image, seed=3)
    broken = {"now": True}

    def check(_data):
        if broken["now"]:
            raise OSError("sensor unplugged")
        return True

    machine.bind("EV_lowEnergy", check=check)
    machine.bind("EV_atCharger", check=lambda _data: True)
    before = (list(machine.states), machine.violations, machine.rng.state)
    with pytest.raises(vm.CallbackError) as caught:
        machine.step()
    assert (caught.value.event, caught.value.kind) == ("EV_lowEnergy", "check")
    assert isinstance(caught.value.__cause__, OSError)
    assert (list(machine.states), machine.violations, machine.rng.state) == before
    broken["now"] = False
    reference = vm.VM(image, seed=3)
    reference.bind("EV_lowEnergy", check=lambda _data: True)
    reference.bind("EV_atCharger", check=lambda _data: True)
    assert machine.step() == reference.step() and machine.states == reference.states


def test_a_raising_action_keeps_its_transition(vm, image):
    machine, reference = vm.VM(image, seed=5), vm.VM(image, seed=5)

    def action(_data):
        raise RuntimeError("motor stalled")

    for m in (machine, reference):
        inputs = random.Random(1)       # one input stream per VM, drawn in the same order
        for e in range(m.num_events):
            if m.image.controllable >> e & 1:
                m.bind(e, action=action if m is machine else (lambda _data: None))
            else:
                m.bind(e, check=lambda _data, inputs=inputs: inputs.random() < 0.3)
    for _ in range(20):
        fired = reference.step()
        if fired and reference.image.controllable >> fired[-1] & 1:
            break
        assert machine.step() == fired
    else:
        pytest.fail("no controllable event fired in 20 steps")
    with pytest.raises(vm.CallbackError) as caught:
        machine.step()
    assert (caught.value.event, caught.value.kind) == (machine.image.event_name(fired[-1]), "action")
    assert isinstance(caught.value.__cause__, RuntimeError)
    assert machine.states == reference.states
