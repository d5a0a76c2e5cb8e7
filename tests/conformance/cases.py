"""Conformance cases shared by every runtime's suite (docs/conformance.md).

A case is one supervisor image, one event script and one run configuration; the reference
trace is what the plain reference VM (runtime_py/swarmvm_reference.py, written beside
docs/semantics.md) prints. Every runtime's suite, the fast Python VM's included, runs the same
cases and compares. Runs
are grouped per supervisor (``batches``) so that an embedded harness builds one firmware per
supervisor and runs every script / option / seed combination in it."""

import itertools
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import python_vm, reference_vm
from swarmvm.readers.event_script import random_script

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


@lru_cache(maxsize=None)
def reference(b, run):
    """The reference VM's trace lines for one run of a batch (the oracle of every runtime)."""
    return list(_reference_lines(b, run))


@lru_cache(maxsize=None)
def _reference_lines(b, run):
    """reference's lines, computed once per case: the plain VM is several times slower than the
    fast one, and the C, C++ and Python suites each compare several builds with them."""
    machine = reference_vm().ReferenceVM(b.image, inputs=run.inputs, control=run.control, policy=run.policy,
                                         seed=run.seed)
    return tuple(python_vm().replay(machine, b.scripts[run.script]))


def _blocks(per_supervisor):
    """Nadzoru's flat layout: each supervisor's states' entries joined, and where each block starts."""
    blocks = [[entry for state in sup for entry in state] for sup in per_supervisor]
    return ",".join(",".join(b) for b in blocks if b), [sum(len(b) for b in blocks[:s]) for s in range(len(blocks))]


def supervisor_yaml(events, controllable, alphabets, states, initial=None, public=None, probabilities=None):
    """A supervisor.yaml in Nadzoru 2's layout, the one model writer of the tests. ``events``: bare
    names in file order; ``controllable``: 0/1 per event; ``alphabets``: per local supervisor, the
    names of its events; ``states``: per local supervisor, per state (in file numbering) its
    transitions as (event name, target state) in file order; ``initial``: per supervisor its initial
    state (default 0); ``public``: 0/1 per event, written as ``ev_shared`` (default: no such key);
    ``probabilities``: per supervisor, per state, the probabilities (text) of its controllable
    transitions in file order, written as ``sup_data_prob`` (default: none)."""
    initial = list(initial) if initial is not None else [0] * len(states)
    entries = [[[str(len(state))] + [x for e, t in state for x in ("EV_" + e, str(t >> 8), str(t & 0xFF))]
                for state in sup] for sup in states]
    data, positions = _blocks(entries)

    def flow(values):
        return "[ %s ]" % ",".join(map(str, values))

    lines = ["num_events: %d" % len(events), "num_supervisors: %d" % len(states),
             "events: " + flow("EV_" + e for e in events), "ev_controllable: " + flow(int(c) for c in controllable)]
    if public is not None:
        lines.append("ev_shared: " + flow(int(p) for p in public))
    lines += ["sup_events: [ %s ]" % ",".join(flow(int(e in alphabet) for e in events) for alphabet in alphabets),
              "sup_init_state: " + flow(initial), "sup_current_state: " + flow(initial),
              "sup_data_pos: " + flow(positions), "sup_data: [ %s ]" % data]
    if probabilities is not None:
        data, positions = _blocks([[[str(len(state))] + list(state) for state in sup] for sup in probabilities])
        lines += ["sup_data_prob_pos: " + flow(positions), "sup_data_prob: [ %s ]" % data]
    return "\n".join(lines) + "\n"


def compiled_image(folder, text, name="s.yaml"):
    """The image of the supervisor.yaml ``text`` (supervisor_yaml's), written as ``folder/name``."""
    path = Path(folder) / name
    path.write_text(text)
    return compile_inputs([str(path)]).image


def one_supervisor_yaml(events, controllable, state_transitions):
    """A supervisor.yaml of one local supervisor of one state whose alphabet is every event, all
    private: ``state_transitions`` its self-loops' event names."""
    return supervisor_yaml(events, controllable, [set(events)], [[[(e, 0) for e in state_transitions]]],
                           public=[0] * len(events))


# An image swapped in by an action while another input fires (docs/semantics.md, "Reset and
# swap"): in FIRST (events c, d controllable; x, y not) x and y are both defined in state 0;
# SECOND has fewer events (b controllable; x, y), so FIRST's index of y (3) is none of
# SECOND's, and in its initial state b is enabled and y has no move.
SWAP_FIRST = supervisor_yaml(["c", "d", "x", "y"], [1, 1, 0, 0], [{"c", "d", "x", "y"}],
                             [[[("c", 1), ("d", 0), ("x", 1), ("y", 0)], [("c", 0), ("x", 0), ("y", 1)]]])
SWAP_SECOND = supervisor_yaml(["b", "x", "y"], [1, 0, 0], [{"b", "x", "y"}],
                              [[[("b", 1), ("x", 0)], [("b", 0), ("x", 1), ("y", 0)]]])
# A violation hook's failure (docs/semantics.md, "Callbacks that raise"): EV_u has no move in
# supervisor 0 and moves supervisor 1 from 0 to 1; controllable EV_c loops in supervisor 0.
HOOKED = supervisor_yaml(["c", "u"], [1, 0], [{"c", "u"}, {"u"}], [[[("c", 0)]], [[("u", 1)], [("u", 1)]]])
