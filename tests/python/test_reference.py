"""The reference VM (runtime_py/swarmvm_reference.py) and the fast VM step alike beyond the
scripted runs of the conformance suite: with callbacks that raise, a violation hook, actions
that rebind or load an image mid-step, policy ``first`` with a priority, policy ``learned`` and
strict mode. Each test runs both VMs side by side on the same callbacks and compares after
every step the outcome (the events, or the error), the states, the violations, the generator's
state and the order in which the callbacks were called."""

import random
import re
from pathlib import Path

import pytest

from conformance.cases import OPTIONS, SUPERVISORS, SWAP_FIRST, SWAP_SECOND, batch, reference_vm
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import learning

LEARN = learning()


def both(vm):
    """The fast VM's class and the reference's."""
    return vm.VM, reference_vm().ReferenceVM


def lockstep(vm, make, bind, steps):
    """For each VM class: ``make(cls)`` a VM, ``bind(machine, log)`` its callbacks (which write
    to ``log``), then ``steps`` steps; the two records must be equal."""
    records = []
    for cls in both(vm):
        machine, log = make(cls), []
        bind(machine, log)
        record = []
        for _ in range(steps):
            try:
                outcome = machine.step()
            except vm.CallbackError as error:
                outcome = (error.event, error.kind, type(error.__cause__).__name__)
            record.append((outcome, list(machine.states), machine.violations, machine.rng.state, log[:]))
            del log[:]
        records.append(record)
    assert records[0] == records[1]
    return records[0]


def noisy_callbacks(seed):
    """A binder whose checks and actions raise now and then, and a violation hook that does
    too; every call logged, each machine drawing from its own generator seeded alike."""
    def bind(machine, log):
        draw = random.Random(seed)

        def check(event):
            log.append(("check", event))
            if draw.random() < 0.03:
                raise KeyError("sensor %d" % event)
            return draw.random() < 0.3

        def action(event):
            log.append(("action", event))
            if draw.random() < 0.03:
                raise ValueError("motor %d" % event)

        def hook(event, sup):
            log.append(("violation", event, sup))
            if draw.random() < 0.2:
                raise OSError("hook")

        for event in range(machine.num_events):
            controllable = machine.image.controllable >> event & 1
            machine.bind(event, action=action, check=None if controllable else check, data=event)
        machine.on_violation = hook
    return bind


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_raising_callbacks_and_the_violation_hook_step_alike(vm, path):
    image = batch(path).image
    raised = 0
    for number, (inputs, control, policy) in enumerate(OPTIONS):
        record = lockstep(vm, lambda cls: cls(image, inputs=inputs, control=control, policy=policy, seed=number + 1),
                          noisy_callbacks(number), 60)
        raised += sum(isinstance(outcome, tuple) for outcome, *_ in record)
    assert raised > 0, "no callback raised: the test would prove nothing"


def test_callbacks_that_rebind_mid_step_step_alike(vm):
    """An action that rebinds a check and changes the policy in the middle of the inputs: the
    rest of the step goes on with the new bindings and policy, in both VMs."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))).image

    def bind(machine, log):
        draw = random.Random(7)

        def check(event):
            return draw.random() < 0.4

        def action(event):
            log.append(event)
            if event % 3 == 0:
                machine.bind(machine.input_order[event % len(machine.input_order)], check=lambda _d: True, data=event)
                machine.policy = "first" if machine.policy == "uniform" else "uniform"
        for event in range(machine.num_events):
            machine.bind(event, action=action, check=None if machine.image.controllable >> event & 1 else check,
                         data=event)
    lockstep(vm, lambda cls: cls(image, seed=3), bind, 80)


def test_an_action_that_loads_an_image_ends_the_step_alike(vm, tmp_path):
    first, second = (tmp_path / "first.yaml", tmp_path / "second.yaml")
    first.write_text(SWAP_FIRST)
    second.write_text(SWAP_SECOND)
    images = [compile_inputs([str(path)]).image for path in (first, second)]

    def bind(machine, log):
        def on_x(_data):
            log.append("x")
            machine.load(images[1] if machine.image.num_events == 4 else images[0])
        machine.bind("EV_x", action=on_x, check=lambda _d: True)
        machine.bind("EV_y", check=lambda _d: True)
    record = lockstep(vm, lambda cls: cls(images[0], seed=5), bind, 6)
    assert record[0][0] == [2], "the load ends the first step after x (FIRST's event 2), before y"


def test_priority_and_the_learned_policy_choose_alike(vm):
    uav = batch(next(p for p in SUPERVISORS if p.endswith("/uav.yaml"))).image
    image = vm.Image.parse(uav)
    last = image.event_name(max(e for e in range(image.num_events) if image.controllable >> e & 1))

    def bind(machine, log):
        draw = random.Random(2)
        for event in machine.input_order:
            machine.bind(event, check=lambda _d: draw.random() < 0.3)
    lockstep(vm, lambda cls: cls(uav, policy="first", priority=[last]), bind, 40)
    policies = []

    def learned(cls):
        policies.append(LEARN.LearnedPolicy(image))
        return cls(uav, policy="learned", learner=policies[-1], seed=9)
    lockstep(vm, learned, bind, 40)
    assert policies[0].theta == policies[1].theta


def test_strict_mode_refuses_alike(vm):
    image = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))).image
    refusals = []
    for cls in both(vm):
        with pytest.raises(vm.UnboundEvents) as refused:
            cls(image, strict=True).step()
        refusals.append(refused.value.names)
    assert refusals[0] == refusals[1] != []


def test_the_reference_reads_the_image_plainly():
    """No code written at run time in the reference: it never calls exec, eval or compile."""
    source = Path(reference_vm().__file__).read_text()
    assert not any(word + "(" in source for word in ("exec", "eval", "compile"))


def test_the_reference_follows_the_semantics_page_step_by_step():
    """docs/semantics.md's numbered steps are the reference's step methods, in the page's order
    (each docstring opens with the step's number and name), and the page's sections the
    reference cites are the page's headings, so that the two are read side by side."""
    page = (Path(__file__).parents[2] / "docs" / "semantics.md").read_text()
    source = Path(reference_vm().__file__).read_text()
    steps = re.findall(r"^(\d)\. \*\*([^.*]+)\.\*\*", page, re.M)
    assert [name for _, name in steps] == ["Poll", "Occurrence", "Apply inputs", "Control phase", "Enabled set",
                                           "Selection"]
    assert re.findall(r'"""(\d)\. ([A-Z][a-z ]+):', source) == steps
    headings = re.findall(r"^#+ (.+)$", page, re.M)
    cited = {"Model", "One step", "Selection policies", "The pseudo-random generator", "Callbacks",
             "Callbacks that raise", "Reset and swap", "Options summary"}
    assert all('"%s"' % section in source and any(h.startswith(section) for h in headings) for section in cited)
    assert "runtime_py/swarmvm_reference.py" in page
