"""Hypothesis strategies for the property tests: random local-modular supervisor sets, names and
event scripts (docs/conformance.md, "Property tests").

A drawn :class:`SupervisorSet` is what a synthesis tool could export: several local supervisors
whose alphabets overlap, controllable and uncontrollable events, public and private ones,
deterministic transitions and every state reachable from its supervisor's initial state (which
need not be state 0). It is written as a Nadzoru 2 ``supervisor.yaml`` by the tests' one model
writer (conformance.cases.supervisor_yaml). Names are drawn to hurt: keywords of C, C++ and
Python, the runtimes' and the targets' own identifiers, a public ``_x`` with ``received_x``,
names up to the format's 255 characters and names that differ only in case."""

import keyword
import string
from dataclasses import dataclass

from hypothesis import strategies as st

from conformance.cases import supervisor_yaml

MAX_NAME = 255      # the image format's longest name (docs/limits.md)

C_KEYWORDS = ("auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum",
              "extern", "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return",
              "short", "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void",
              "volatile", "while", "_Bool", "_Complex", "_Static_assert")
CPP_KEYWORDS = ("and", "bool", "catch", "class", "constexpr", "delete", "explicit", "false", "final", "friend",
                "mutable", "namespace", "new", "noexcept", "not", "nullptr", "operator", "or", "override", "private",
                "protected", "public", "template", "this", "throw", "true", "try", "typename", "using", "virtual",
                "xor", "co_await", "concept", "requires")
# Identifiers the C library, the runtimes, kilolib, ARGoS and the generated code use themselves.
OWN_NAMES = ("NULL", "EOF", "main", "errno", "assert", "printf", "stream", "svm", "svm_sct", "swarmvm", "SVM",
             "svm_step", "svm_vm", "message", "message_t", "kilo_ticks", "setup", "loop", "data", "vm", "image",
             "tables", "IMAGE", "NAMES", "NUM_EVENTS", "NUM_SUPERVISORS", "SCT", "Controller", "Init", "Reset",
             "Destroy", "ControlStep", "Send", "Heard", "robot", "self", "time", "std", "argos", "kImage", "x",
             "received_x", "_x", "X", "on_x", "check_x", "EV_x", "_", "a__b", "uint8_t", "int8_t", "size_t")
AWKWARD = tuple(dict.fromkeys(C_KEYWORDS + CPP_KEYWORDS + tuple(keyword.kwlist) + OWN_NAMES))

IDENTIFIER_CHARS = string.ascii_letters + string.digits + "_"


def names():
    """One name, as the file format allows it: 1 to 255 of [A-Za-z0-9_]; mostly short, often awkward."""
    return st.one_of(
        st.sampled_from(AWKWARD),
        st.text(IDENTIFIER_CHARS, min_size=1, max_size=12),
        st.text(IDENTIFIER_CHARS, min_size=MAX_NAME - 8, max_size=MAX_NAME),
    )


@st.composite
def event_names(draw, min_size=1, max_size=8):
    """Distinct event names; some pairs differ only in case, some are ``_x`` with ``received_x``,
    some share a prefix (``x`` and ``x2``: one Kilobot message when ``x`` is 9 characters or more)."""
    found = draw(st.lists(names(), min_size=min_size, max_size=max_size, unique=True))
    extra = []
    if found and draw(st.booleans()):
        base = found[0]
        extra.append(draw(st.sampled_from([base.swapcase(), base.upper(), base.lower(), "received" + base,
                                          "_" + base, base[1:] or base + "_", base + "2"])))
    return list(dict.fromkeys(found + [e for e in extra if 0 < len(e) <= MAX_NAME]))


@dataclass(frozen=True)
class SupervisorSet:
    """A drawn supervisor set in file terms: states numbered as in the file, events by bare name."""
    events: tuple            # bare names, file order
    controllable: tuple      # 0/1 per event
    public: tuple            # 0/1 per event
    alphabets: tuple         # per local supervisor: frozenset of event names
    states: tuple            # per local supervisor, per file state: ((event, target), ...) in file order
    initial: tuple           # per local supervisor: its initial state (file numbering)
    probabilities: tuple | None = None   # per supervisor, per state: its controllable transitions' (text)

    def yaml(self):
        return supervisor_yaml(self.events, self.controllable, self.alphabets, self.states, self.initial, self.public,
                               self.probabilities)

    @property
    def uncontrollable(self):
        return [e for e, c in zip(self.events, self.controllable) if not c]


@st.composite
def local_supervisor(draw, alphabet, max_states=5):
    """One deterministic automaton over ``alphabet`` (a list of names) whose states are all
    reachable from the initial one: a random spanning tree from the initial state, then random
    extra transitions where a state still has the event free; states numbered at random."""
    count = draw(st.integers(1, max_states))
    free = [list(alphabet) for _ in range(count)]       # events not yet used, per state (tree order)
    edges = [[] for _ in range(count)]
    for state in range(1, count):
        parent = draw(st.sampled_from([p for p in range(state) if free[p]]))
        event = draw(st.sampled_from(free[parent]))
        free[parent].remove(event)
        edges[parent].append((event, state))
    for state in range(count):
        for event in draw(st.lists(st.sampled_from(free[state]), unique=True)) if free[state] else []:
            edges[state].append((event, draw(st.integers(0, count - 1))))
    number = draw(st.permutations(range(count)))        # file number of each tree-order state
    states = [None] * count
    for state in range(count):
        states[number[state]] = tuple(draw(st.permutations([(e, number[t]) for e, t in edges[state]])))
    return tuple(states), number[0]


@st.composite
def supervisor_sets(draw, max_events=8, max_supervisors=4, max_states=5):
    """A local-modular supervisor set: every event in the alphabet of one or more supervisors
    (so supervisors share events), each supervisor's alphabet non-empty."""
    events = draw(event_names(max_size=max_events))
    n = draw(st.integers(1, max_supervisors))
    owners = [draw(st.sets(st.integers(0, n - 1), min_size=1)) for _ in events]
    for s in range(n):                                   # no supervisor without events
        if not any(s in o for o in owners):
            owners[draw(st.integers(0, len(events) - 1))].add(s)
    alphabets = tuple(frozenset(e for e, o in zip(events, owners) if s in o) for s in range(n))
    controllable = tuple(draw(st.integers(0, 1)) for _ in events)
    public = tuple(draw(st.integers(0, 1)) for _ in events)
    drawn = [draw(local_supervisor(sorted(alphabets[s]), max_states)) for s in range(n)]
    states = tuple(d[0] for d in drawn)
    probabilities = None
    if draw(st.booleans()):      # Nadzoru 2's probabilistic keys, for the weighted policy
        chosen = {e for e, c in zip(events, controllable) if c}
        probabilities = tuple(tuple(tuple(draw(PROBABILITIES) for e, _ in state if e in chosen) for state in sup)
                              for sup in states)
    return SupervisorSet(tuple(events), controllable, public, alphabets, states, tuple(d[1] for d in drawn),
                         probabilities)


# Probabilities as Nadzoru 2 and people write them: decimals, ratios, the bounds.
PROBABILITIES = st.one_of(
    st.sampled_from(("0", "1", "0.5", "0.25", "1/3", "2/3", "0.1", "0.99999999", "1e-2", "1.0")),
    st.fractions(0, 1, max_denominator=1000).map(lambda f: "%d/%d" % (f.numerator, f.denominator)),
)


def scripts(supervisor_set, min_steps=1, max_steps=12):
    """An event script for the set: per step, the uncontrollable events (bare names) that occur."""
    events = supervisor_set.uncontrollable
    row = st.frozensets(st.sampled_from(events)) if events else st.just(frozenset())
    return st.lists(row, min_size=min_steps, max_size=max_steps)


RUN_OPTIONS = st.fixed_dictionaries({
    "inputs": st.sampled_from(("level", "edge")),
    "control": st.sampled_from(("after-inputs", "if-quiet")),
    "policy": st.sampled_from(("uniform", "first", "weighted")),
    "seed": st.integers(0, 0xFFFFFFFF),
})

# Model names for --name: ordinary identifiers (most often), the C library's, the runtimes' and the
# targets' own identifiers, a few keywords (refused), any text (non-ASCII, spaces: made identifiers),
# names around the longest allowed.
MODEL_NAMES = st.one_of(st.from_regex(r"[a-z][a-z0-9_]{0,15}", fullmatch=True),
                        st.sampled_from(OWN_NAMES + ("int", "class", "lambda", "None")),
                        st.text(min_size=1, max_size=12),
                        st.text(string.ascii_lowercase, min_size=230, max_size=MAX_NAME))
