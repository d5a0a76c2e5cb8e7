"""The fast VM's written-out step held to what ordinary code gets for free: a traceback through it
shows its lines (it is compiled under a file name of its own that ``linecache`` knows); its
contract with the VM (the members it reads and writes on ``vm`` and ``sct``, the names ``make``
receives) is checked by parsing it, so a rename on either side fails here rather than in a rare
branch at run time; and the generator's draw is XorShift32's, called, not retyped."""

import ast
import builtins
import linecache
import traceback

import pytest

from conformance.cases import OPTIONS, SUPERVISORS, batch


def installed(machine, name):
    """The source of the written-out function installed on ``machine`` as ``name``."""
    code = machine.__dict__[name].__func__.__code__
    lines = linecache.getlines(code.co_filename)
    assert lines, "no lines for %s" % code.co_filename
    return code.co_filename, "".join(lines)


def stepped_vms(vm):
    """(a VM, its step's source) for every corpus supervisor under every option, strict or not:
    each shape of step the VM writes (one or several supervisors, total inputs or not, ...)."""
    for path in SUPERVISORS:
        image = batch(path).image
        for (inputs, control, policy), strict in zip(OPTIONS * 2, [False] * len(OPTIONS) + [True] * len(OPTIONS)):
            machine = vm.VM(image, inputs=inputs, control=control, policy=policy, strict=strict)
            for event in machine.input_order:
                machine.bind(event, check=lambda _data: True)
            machine.bind(machine.image.event_name(0), action=lambda _data: None)
            machine.step()
            yield machine, installed(machine, "step")[1]


def stepped_scts(vm):
    """(an exact-mode SCT, its step's source) for every corpus supervisor, SCT and SCTPub."""
    for path in SUPERVISORS:
        for cls in (vm.SCT, vm.SCTPub):
            sct = cls(path)
            events, controllable = sct.get_events()
            for index in events.values():
                sct.add_callback(index, lambda _data: None, None if controllable[index] else lambda _data: True, None)
            sct.run_step()
            yield sct, installed(sct, "run_step")[1]


def attribute_chains(tree, root):
    """Every chain of attributes read or written on the name ``root`` (``vm.rng.below`` gives
    ``("rng", "below")``), longest only."""
    chains = set()
    for node in ast.walk(tree):
        names = []
        while isinstance(node, ast.Attribute):
            names.append(node.attr)
            node = node.value
        if isinstance(node, ast.Name) and node.id == root and names:
            chains.add(tuple(reversed(names)))
    return {chain for chain in chains if not any(other[:len(chain)] == chain != other for other in chains)}


def missing_members(obj, chains):
    """The chains of ``chains`` that ``obj`` lacks a member of."""
    missing = []
    for chain in chains:
        value = obj
        for name in chain:
            if not hasattr(value, name):
                missing.append(".".join(chain))
                break
            value = getattr(value, name)
    return missing


def unbound_names(tree):
    """Names the source reads that nothing defines: neither a parameter of ``make`` or of the
    step, nor a name it assigns, nor a builtin."""
    defined = set(dir(builtins))
    for node in ast.walk(tree):
        if isinstance(node, ast.arg):
            defined.add(node.arg)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            defined.add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.ExceptHandler)) and node.name:
            defined.add(node.name)
    return {node.id for node in ast.walk(tree)
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in defined}


def test_the_written_out_steps_use_only_what_the_vm_and_sct_have(vm):
    """Every member the generated steps use on ``vm`` (and, in exact mode, on ``sct``) exists on
    a VM (an SCT) that ran them, and every name they read is defined."""
    seen = set()
    for machine, source in stepped_vms(vm):
        tree = ast.parse(source)
        assert missing_members(machine, attribute_chains(tree, "vm")) == [], source
        assert unbound_names(tree) == set(), source
        seen.add(source)
    for sct, source in stepped_scts(vm):
        tree = ast.parse(source)
        assert missing_members(sct, attribute_chains(tree, "sct")) == [], source
        assert missing_members(sct.vm, attribute_chains(tree, "vm")) == [], source
        assert unbound_names(tree) == set(), source
        seen.add(source)
    assert len(seen) > 20, "the corpus should make many shapes of step"


def test_a_check_named_in_the_step_but_missing_on_the_vm_is_found(vm):
    """The check of the test above on a step that calls a member the VM does not have."""
    tree = ast.parse("def make(plan):\n    def step(vm):\n        vm._renamed_plan(plan)\n    return step\n")
    machine = vm.VM(batch(SUPERVISORS[0]).image)
    assert missing_members(machine, attribute_chains(tree, "vm")) == ["_renamed_plan"]
    assert unbound_names(ast.parse("def make(a):\n    return a + b\n")) == {"b"}


def test_a_traceback_through_the_step_shows_its_lines(vm):
    image = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))).image
    machine = vm.VM(image)
    for event in machine.input_order:
        machine.bind(event, check=lambda _data: True, action=lambda _data: 1 / 0)
    with pytest.raises(vm.CallbackError) as raised:
        machine.step()
    text = "".join(traceback.format_exception(raised.value))
    filename, source = installed(machine, "step")
    assert filename.startswith("<swarmvm canonical step ") and 'File "%s", line ' % filename in text
    shown = text.split('File "%s", line ' % filename, 1)[1].splitlines()[1].strip()
    assert shown == "vm._act(event, a[event])" and shown in source


def test_a_traceback_through_the_exact_step_shows_its_lines(vm):
    """Exact mode raises a check's exception as it is (as the published VM): the traceback
    names the written-out step and shows the check's call."""
    sct = vm.SCT(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    events, controllable = sct.get_events()
    for index in events.values():
        if not controllable[index]:
            sct.add_callback(index, None, lambda _data: {}["broken sensor"], None)
    with pytest.raises(KeyError) as raised:
        sct.run_step()
    filename, _ = installed(sct, "run_step")
    text = "".join(traceback.format_exception(raised.value))
    assert filename.startswith("<swarmvm exact step ")
    assert text.split('File "%s", line ' % filename, 1)[1].splitlines()[1].strip().startswith("if c0(d0):")


def test_the_uniform_draw_is_the_generators_own(vm):
    """The step draws by calling XorShift32.next (the formula exists once, not retyped in the
    step's text): a generator whose ``next`` is replaced sees every draw of a uniform choice."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))).image
    calls = []

    class Counting(vm.XorShift32):
        def next(self):
            calls.append(self.state)
            return super().next()

    machine, plain = vm.VM(image, seed=4), vm.VM(image, seed=4)
    machine.rng = Counting(4)
    for m in (machine, plain):
        for k, event in enumerate(m.input_order):
            m.bind(event, check=lambda _data, k=k, m=m: (m.rng.state >> k) & 1)
    draws = 0
    for _ in range(50):
        before = plain.rng.state
        assert machine.step() == plain.step()
        draws += plain.rng.state != before
    assert draws > 0 and len(calls) == draws
