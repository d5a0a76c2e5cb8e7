"""Conformance of the Python VMs: the fast VM prints the reference VM's trace, and both agree
with an independent reading of each input file.

The reference (runtime_py/swarmvm_reference.py, the plain step of docs/semantics.md) is the
oracle of every runtime's suite (cases.reference); the fast VM (runtime_py/swarmvm_vm.py, its step
written out per plan) is one of those runtimes, compared here step by step, generator state
included.

The oracle below reads the supervisor.yaml with PyYAML's safe loader and walks Nadzoru's flat
``sup_data`` itself: it shares no code with the compiler's loader, canonical form or tables.
For every corpus supervisor, every option combination, several seeds and random scripts it
checks, step by step, that the VM (1) reports exactly the enabled set the file implies,
(2) fires exactly the uncontrollable events the script and input mode imply, in input order,
(3) picks a controllable event only when one is enabled, from the enabled set (the first by name
under policy ``first``), (4) counts the same violations, and (5) keeps states that are a
consistent renaming of the file's states.
"""

from types import SimpleNamespace

import pytest

from conformance.cases import SUPERVISORS, batch
from swarmvm.compiler.runtime_files import reference_vm
from conformance.file_oracle import FileOracle


def check_run(vm_module, oracle, b, run):
    machine = vm_module.VM(b.image, inputs=run.inputs, control=run.control, policy=run.policy, seed=run.seed)
    name = machine.image.event_name
    row = {"events": set()}
    for e in machine.input_order:
        machine.bind(e, check=lambda _d, e=name(e): e in row["events"])
    cur, violations, previous = list(oracle.initial), 0, set()
    renaming = [dict() for _ in cur]
    for number, script_row in enumerate(b.scripts[run.script], 1):
        where = "%s %s step %d" % (b.name, run, number)
        assert {name(e) for e in machine.enabled()} == oracle.enabled(cur), where
        row["events"] = {name(e) for e in script_row}
        occurred = row["events"] - previous if run.inputs == "edge" else row["events"]
        previous = row["events"]
        expected = [e for e in oracle.input_order if e in occurred]
        fired = [name(e) for e in machine.step()]
        assert fired[:len(expected)] == expected, where
        for event in expected:
            violations += oracle.apply(cur, event)
        choice = fired[len(expected):]
        options = oracle.enabled(cur)
        if (expected and run.control == "if-quiet") or not options:
            assert choice == [], where
        else:
            assert len(choice) == 1 and choice[0] in options, where
            if run.policy == "first":
                assert choice[0] == min(options), where
            assert oracle.apply(cur, choice[0]) == 0
        assert machine.violations == violations, where
        for s, state in enumerate(cur):
            assert renaming[s].setdefault(state, machine.states[s]) == machine.states[s], where
            assert len(set(renaming[s].values())) == len(renaming[s]), where


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.split("/")[-1])
def test_python_vm_agrees_with_the_file(vm, path):
    b = batch(path)
    oracle = FileOracle(path)
    for run in b.runs:
        check_run(vm, oracle, b, run)


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.split("/")[-1])
def test_reference_vm_agrees_with_the_file(path):
    b = batch(path)
    oracle = FileOracle(path)
    for run in b.runs:
        check_run(SimpleNamespace(VM=reference_vm().ReferenceVM), oracle, b, run)


def scripted(machine, script):
    """``machine`` from reset with checks answering ``script``'s rows: (the events of each
    step, the states, violations and generator state after it)."""
    row: dict = {"events": frozenset()}
    for event in machine.input_order:
        machine.bind(event, check=lambda _data, event=event: event in row["events"])
    machine.reset()
    after = []
    for row["events"] in script:
        after.append((machine.step(), list(machine.states), machine.violations, machine.rng.state))
    return after


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.split("/")[-1])
def test_fast_vm_steps_as_the_reference(vm, path):
    """Every run of the batch: the same events, states, violations and generator state after
    every step (the trace lines compare the first three; the generator's state shows a draw
    made or skipped before it changes a choice)."""
    b = batch(path)
    for run in b.runs:
        options = dict(inputs=run.inputs, control=run.control, policy=run.policy, seed=run.seed)
        fast = scripted(vm.VM(b.image, **options), b.scripts[run.script])
        plain = scripted(reference_vm().ReferenceVM(b.image, **options), b.scripts[run.script])
        assert fast == plain, "%s %s" % (b.name, run)


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.split("/")[-1])
def test_the_seed_decides_among_several_enabled_events(vm, path):
    """Same script, different seeds: wherever two or more events were ever enabled together,
    some seed must choose differently; where never, every seed gives the same trace."""
    b = batch(path)
    script = b.scripts[-1]
    traces, choices = set(), False
    for seed in range(1, 9):
        machine = vm.VM(b.image, seed=seed)
        row = {"events": frozenset()}
        for e in machine.input_order:
            machine.bind(e, check=lambda _d, e=e: e in row["events"])
        trace = []
        for script_row in script:
            row["events"] = script_row
            before = list(machine.states)
            fired = machine.step()
            # The enabled set the choice was made from, re-derived from the states after inputs.
            probe = vm.VM(b.image)
            probe.states = before
            for e in fired:
                if not machine.image.controllable >> e & 1:
                    probe._apply(e)
            choices = choices or len(probe.enabled()) > 1
            trace.append(tuple(fired))
        traces.add(tuple(trace))
    assert (len(traces) > 1) == choices
