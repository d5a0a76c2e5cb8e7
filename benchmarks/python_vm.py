"""Python VM steps per second on every corpus supervisor, against the plain reference VM and a
dictionary-walking baseline.

The reference (runtime_py/swarmvm_reference.py) is the step of docs/semantics.md written
plainly over the same image: the ratio to it is what the fast VM's written-out step gains. The
baseline is written here the way the published Python VM works: events looked up in a
dictionary by name, a supervisor's state found by walking the flat ``sup_data`` list from the
start of its block, transitions found by scanning the state's list, the enabled set built
event by event. Both run the same random script under the same rules (level inputs, controllable
event after the inputs, uniform choice); the table prints steps per second and the ratios."""

import sys
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from conformance.cases import SUPERVISORS, reference_vm  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm.compiler.runtime_files import python_vm  # noqa: E402
from swarmvm.readers.event_script import random_script  # noqa: E402

STEPS = 20000


class DictWalkingVM:
    """A straightforward VM over the file's own lists (the baseline, not the product)."""

    def __init__(self, path, seed):
        doc = yaml.safe_load(Path(path).read_text())
        self.EV = {name: i for i, name in enumerate(doc["events"])}
        self.n = doc["num_events"]
        self.controllable = doc["ev_controllable"]
        self.sup_events = doc["sup_events"]
        self.pos = doc["sup_data_pos"]
        self.data = doc["sup_data"]
        self.state = list(doc["sup_init_state"])
        self.inputs = set()
        self.rng = python_vm().XorShift32(seed)

    def position(self, sup, state):
        pos = self.pos[sup]
        for _ in range(state):
            pos += self.data[pos] * 3 + 1
        return pos

    def transition(self, event):
        for sup in range(len(self.state)):
            if self.sup_events[sup][event]:
                pos = self.position(sup, self.state[sup])
                for k in range(self.data[pos]):
                    if self.EV[self.data[pos + 1 + 3 * k]] == event:
                        self.state[sup] = self.data[pos + 2 + 3 * k] * 256 + self.data[pos + 3 + 3 * k]
                        break

    def enabled(self):
        active = [1 if c else 0 for c in self.controllable]
        for sup in range(len(self.state)):
            disabled = list(self.sup_events[sup])
            pos = self.position(sup, self.state[sup])
            for k in range(self.data[pos]):
                disabled[self.EV[self.data[pos + 1 + 3 * k]]] = 0
            for e in range(self.n):
                if disabled[e]:
                    active[e] = 0
        return [e for e in range(self.n) if active[e]]

    def step(self):
        for e in range(self.n):
            if not self.controllable[e] and e in self.inputs:
                self.transition(e)
        enabled = self.enabled()
        if enabled:
            self.transition(enabled[self.rng.below(len(enabled))] if len(enabled) > 1 else enabled[0])


def rate(step, feed, rows):
    start = time.process_time()
    for row in rows:
        feed(row)
        step()
    return len(rows) / (time.process_time() - start)


def scripted_rate(machine, rows):
    """Steps per second of ``machine`` (either Python VM) replaying ``rows`` through its checks."""
    row = {"now": set()}
    for e in machine.input_order:
        machine.bind(e, check=lambda _d, e=e: e in row["now"])
    return rate(machine.step, lambda r: row.__setitem__("now", r), rows)


def main():
    vm = python_vm()
    print("| supervisor | swarmvm steps/s | reference steps/s | ratio | baseline steps/s | ratio |")
    print("|---|---|---|---|---|---|")
    for path in SUPERVISORS:
        compiled = compile_inputs([path])
        rows = random_script(compiled.tables, STEPS, seed=1)
        ours = scripted_rate(vm.VM(compiled.image), rows)
        plain = scripted_rate(reference_vm().ReferenceVM(compiled.image), rows)
        baseline = DictWalkingVM(path, seed=1)
        by_name = {name: i for i, name in enumerate(compiled.model.events)}
        file_index = {i: baseline.EV["EV_" + name] for name, i in by_name.items()}
        file_rows = [{file_index[e] for e in r} for r in rows]
        theirs = rate(baseline.step, lambda r: setattr(baseline, "inputs", r), file_rows)
        print("| %s | %.0f | %.0f | %.1fx | %.0f | %.1fx |" % (Path(path).stem, ours, plain, ours / plain, theirs,
                                                             ours / theirs))


if __name__ == "__main__":
    main()
