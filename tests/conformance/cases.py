"""Conformance cases shared by every runtime's suite (docs/conformance.md).

A case is one supervisor image, one event script and one run configuration; the reference
trace is what the Python VM prints. A runtime's suite runs the same cases and compares. Runs
are grouped per supervisor (``batches``) so that an embedded harness builds one firmware per
supervisor and runs every script / option / seed combination in it."""

import itertools
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from swarmvm.pipeline import compile_inputs
from swarmvm.runtime import python_vm
from swarmvm.script import random_script

CORPUS = Path(__file__).resolve().parent.parent / "corpus"
SUPERVISORS = sorted(str(p) for p in CORPUS.glob("*/*.yaml"))
INPUTS = ("level", "edge")
CONTROLS = ("after-inputs", "if-quiet")
POLICIES = ("uniform", "first", "weighted")
OPTIONS = tuple(itertools.product(INPUTS, CONTROLS, POLICIES))
SEEDS = (1, 42, 0xDEADBEEF)
STEPS = 40


@dataclass(frozen=True)
class Run:
    inputs: str
    control: str
    policy: str
    seed: int
    script: int        # index into the batch's scripts


@dataclass(frozen=True)
class Batch:
    name: str          # supervisor file stem
    path: str
    image: bytes
    scripts: tuple     # tuple of scripts; a script is a tuple of frozensets of event indices
    runs: tuple        # tuple of Run


@lru_cache(maxsize=None)
def batch(path, steps=STEPS):
    """Every option combination x seed for one supervisor; one random script per seed."""
    compiled = compile_inputs([path])
    scripts = tuple(tuple(frozenset(r) for r in random_script(compiled.tables, steps, seed, density))
                    for seed in SEEDS for density in (0.15, 0.4))
    runs = tuple(Run(i, c, p, seed, k) for k, seed in enumerate(s for s in SEEDS for _ in (0, 1))
                 for i, c, p in OPTIONS)
    return Batch(Path(path).stem, path, compiled.image, scripts, runs)


def batches():
    return [batch(p) for p in SUPERVISORS]


def reference(b, run):
    """The Python VM's trace lines for one run of a batch."""
    vm = python_vm()
    machine = vm.VM(b.image, inputs=run.inputs, control=run.control, policy=run.policy, seed=run.seed)
    return vm.replay(machine, b.scripts[run.script])


def one_supervisor_yaml(events, controllable, sup_data):
    """A supervisor.yaml of one local supervisor whose alphabet is every event, all private:
    ``events`` bare names, ``controllable`` 0/1 per event, ``sup_data`` its flat block (as text)."""
    n = len(events)
    return ("num_events: %d\nnum_supervisors: 1\nevents: [ %s ]\nev_controllable: [ %s ]\nev_shared: [ %s ]\n"
            "sup_events: [ [ %s ] ]\nsup_init_state: [ 0 ]\nsup_current_state: [ 0 ]\nsup_data_pos: [ 0 ]\n"
            "sup_data: [ %s ]\n" % (n, ",".join("EV_" + e for e in events), ",".join(map(str, controllable)),
                                    ",".join(["0"] * n), ",".join(["1"] * n), sup_data))
