"""The conjunction of a set of local supervisors: their synchronous product, built breadth-first.

A product state is the vector of every supervisor's state. An event can occur in it when every
supervisor whose alphabet holds the event has a transition on it (a supervisor never blocks an
event outside its alphabet); then each such supervisor moves and the others stay. This is the
language the VM's enabled set follows (docs/semantics.md, step 5); equivalence, pictures and the
property checks all read it from here."""

from collections import deque
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

from .errors import InputError
from .model import Model

Vector = Tuple[int, ...]


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


def step(model: Model, vector: Vector, event: int) -> Optional[Vector]:
    """The product state after ``event``, or None if some supervisor holding it blocks it."""
    out = list(vector)
    for s, sup in enumerate(model.supervisors):
        if event in sup.alphabet:
            target = next((t for e, t, _ in sup.states[vector[s]] if e == event), None)
            if target is None:
                return None
            out[s] = target
    return tuple(out)


def build_product(model: Model, limit: int = 1_000_000) -> Product:
    """The reachable product; InputError when it has more than ``limit`` states."""
    start = tuple(0 for _ in model.supervisors)
    number: Dict[Vector, int] = {start: 0}
    vectors, edges = [start], []
    parent: List[Optional[Tuple[int, int]]] = [None]
    queue = deque([start])
    while queue:
        vector = queue.popleft()
        row = []
        for event in range(len(model.events)):
            target = step(model, vector, event)
            if target is None:
                continue
            if target not in number:
                if len(vectors) >= limit:
                    raise InputError(model.source, "", "the product of the supervisors has over %d states" % limit)
                number[target] = len(vectors)
                vectors.append(target)
                parent.append((number[vector], event))
                queue.append(target)
            row.append((event, number[target]))
        edges.append(tuple(row))
    return Product(tuple(vectors), tuple(edges), tuple(parent))
