"""The conjunction of a set of local supervisors: their synchronous product, built breadth-first
under a budget.

A product state is the vector of every supervisor's state. An event can occur in it when every
supervisor whose alphabet holds the event has a transition on it (a supervisor never blocks an
event outside its alphabet); then each such supervisor moves and the others stay. This is the
language the VM's enabled set follows (docs/semantics.md, step 5); equivalence, pictures, the
property checks and synthesis's size estimate all read it from here.

A product can have exponentially many states (twenty independent two-state supervisors: a
million), so every walk of it counts what it explores against a :class:`Budget` and refuses,
in one line, as soon as it is over: the cost of a refusal is the budget's, never the
product's (docs/limits.md)."""

import math
from collections import deque
from dataclasses import dataclass
from typing import Dict, Iterable, Iterator, List, Optional, Sequence, Tuple

from ..boundary.errors import InputError
from ..compiler.model import Model

Vector = Tuple[int, ...]

# Product states a verb explores before it stops: small enough for the slowest verb, `check
# --properties`, to answer interactively on a small machine (docs/limits.md has its time and memory).
DEFAULT_MAX_STATES = 20_000
# Transitions held per state of the budget: a product of many events has many edges per state,
# and edges, not states, are most of its memory.
TRANSITIONS_PER_STATE = 16


class OverBudget(InputError):
    """A product over its budget; ``figure`` says which one was passed: "states" or "transitions"."""

    def __init__(self, source: str, message: str, figure: str, where: str = ""):
        super().__init__(source, "--max-states", message, where)
        self.figure = figure


@dataclass(frozen=True)
class Budget:
    """How much of a product a verb may explore: ``max_states`` states and ``max_transitions``
    transitions (by default ``TRANSITIONS_PER_STATE`` per state). ``source`` and ``where``
    name the input in the refusal, ``what`` the product being explored."""
    source: str
    max_states: int = DEFAULT_MAX_STATES
    what: str = "the product of the supervisors"
    max_transitions: Optional[int] = None
    where: str = ""

    def surely_within(self, bound: int) -> bool:
        """True when an upper bound on the states (:func:`state_bound`) is within the budget."""
        return bound <= self.max_states

    def check(self, states: int, transitions: int = 0) -> None:
        """:class:`OverBudget` when ``states`` or ``transitions`` explored so far are over the budget."""
        max_transitions = self.max_transitions or self.max_states * TRANSITIONS_PER_STATE
        if states > self.max_states:
            self._refuse("states", "%d states, over the budget of %d states" % (states, self.max_states))
        if transitions > max_transitions:
            self._refuse("transitions", "%d transitions, over the budget of %d transitions (%d per state)"
                         % (transitions, max_transitions, TRANSITIONS_PER_STATE))

    def _refuse(self, figure: str, figures: str) -> None:
        raise OverBudget(self.source, "%s reached %s; raise it with --max-states N (max_states= in the API)"
                         % (self.what, figures), figure, self.where)


def state_bound(state_counts: Sequence[int]) -> int:
    """An upper bound on a product's states, from its factors' state counts: their product."""
    return math.prod(state_counts)


@dataclass(frozen=True)
class Product:
    """Reachable product states (index 0 is the initial one) and, per state, its transitions
    as (event index, target state index) in event order; ``parent`` gives each state's
    breadth-first predecessor and event, so :meth:`word` is a shortest path to it."""
    vectors: Tuple[Vector, ...]
    edges: Tuple[Tuple[Tuple[int, int], ...], ...]
    parent: Tuple[Optional[Tuple[int, int]], ...]

    def word(self, state: int) -> List[int]:
        """A shortest event sequence (event indices) from the initial state to ``state``."""
        out = []
        step = self.parent[state]
        while step is not None:
            state, event = step
            out.append(event)
            step = self.parent[state]
        return out[::-1]


class Conjunction:
    """The product's transition function over automata with events numbered 0..events-1:
    ``delta[s][q]`` is automaton s's {event: target} in state q, ``alphabets[s]`` its events
    (an event in no alphabet is never blocked), ``start`` the initial vector. Each state's enabled events are one AND of per-automaton
    bit masks, so a state costs its automata and its transitions, not every event."""

    def __init__(self, events: int, alphabets: Sequence[frozenset[int]], delta: Sequence[Sequence[Dict[int, int]]],
                 start: Vector):
        self.delta, self.start = delta, start
        self.holders = [[s for s, alphabet in enumerate(alphabets) if e in alphabet] for e in range(events)]
        self.everything = (1 << events) - 1
        self.alphabets = [_mask(alphabet) for alphabet in alphabets]
        self.allowed = [[self.everything & ~alphabet | _mask(row) for row in rows]
                        for alphabet, rows in zip(self.alphabets, delta)]

    @classmethod
    def of(cls, model: Model) -> "Conjunction":
        """The conjunction of a canonical model's supervisors (each starts in state 0)."""
        return cls(len(model.events), [sup.alphabet for sup in model.supervisors],
                   [[{e: t for e, t, _ in row} for row in sup.states] for sup in model.supervisors],
                   tuple(0 for _ in model.supervisors))

    def step(self, vector: Vector, event: int) -> Optional[Vector]:
        """The product state after ``event``, or None if some supervisor holding it blocks it."""
        out = list(vector)
        for s in self.holders[event]:
            target = self.delta[s][vector[s]].get(event)
            if target is None:
                return None
            out[s] = target
        return tuple(out)

    def enabled(self, vector: Vector) -> int:
        """The events enabled in ``vector``, as a bit mask."""
        enabled = self.everything
        for s, q in enumerate(vector):
            enabled &= self.allowed[s][q]
        return enabled

    def offered(self, vector: Vector) -> int:
        """The events some automaton holding them has a transition on in ``vector``, as a bit mask."""
        offered = 0
        for s, q in enumerate(vector):
            offered |= self.allowed[s][q] & self.alphabets[s]
        return offered

    def moves(self, vector: Vector) -> Iterator[Tuple[int, Vector]]:
        """(event, next vector) for every event enabled in ``vector``, in event order."""
        for event in events_of(self.enabled(vector)):
            out = list(vector)
            for s in self.holders[event]:
                out[s] = self.delta[s][vector[s]][event]
            yield event, tuple(out)


def _mask(events: Iterable[int]) -> int:
    return sum(1 << e for e in events)


def events_of(mask: int) -> Iterator[int]:
    """The event indices of a non-negative bit mask, in increasing order."""
    while mask:
        yield (mask & -mask).bit_length() - 1
        mask &= mask - 1


def explore(conjunction: Conjunction, budget: Budget) -> Product:
    """The reachable product, breadth-first; InputError (:meth:`Budget.check`) as soon as
    the states or transitions found are over ``budget``."""
    start = conjunction.start
    number: Dict[Vector, int] = {start: 0}
    vectors, edges = [start], []
    parent: List[Optional[Tuple[int, int]]] = [None]
    queue = deque([start])
    transitions = 0
    while queue:
        vector = queue.popleft()
        row = []
        for event, target in conjunction.moves(vector):
            if target not in number:
                number[target] = len(vectors)
                vectors.append(target)
                parent.append((number[vector], event))
                queue.append(target)
            row.append((event, number[target]))
        edges.append(tuple(row))
        transitions += len(row)
        budget.check(len(vectors), transitions)
    return Product(tuple(vectors), tuple(edges), tuple(parent))


def build_product(model: Model, max_states: int = DEFAULT_MAX_STATES) -> Product:
    """The reachable product of ``model``'s supervisors; InputError naming ``--max-states``
    when it has more than ``max_states`` states (or more transitions than that budget holds)."""
    return explore(Conjunction.of(model), Budget(model.source, max_states))
