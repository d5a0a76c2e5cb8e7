"""Are two supervisor sets the same controller? Same events (names, controllable, public) and
the same language of their conjunctions (closed languages: every state marked, as the VM runs
them), whatever their state numbering or their split into local supervisors.

The languages are compared by a breadth-first walk of the pair product: the first pair of
states where one side allows an event the other does not gives a shortest distinguishing
event sequence."""

from collections import deque
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

from ..boundary.escape import terminal
from ..compiler.model import Model
from .product import DEFAULT_MAX_STATES, Budget, Conjunction, Vector, events_of


@dataclass(frozen=True)
class Difference:
    """Why two sets differ: an event-set difference (``events``) or a shortest word that one
    conjunction accepts and the other does not (``word``, accepted by side ``allowed_by``)."""
    events: Tuple[str, ...] = ()
    word: Tuple[str, ...] = ()
    allowed_by: str = ""
    reason: str = ""


def _flags(model: Model) -> Dict[str, Tuple[bool, bool]]:
    return {n: (model.controllable[i], model.public[i]) for i, n in enumerate(model.events)}


def compare(a: Model, b: Model, max_states: int = DEFAULT_MAX_STATES) -> Optional[Difference]:
    """None when ``a`` and ``b`` are equivalent, else the first :class:`Difference` found.
    The walk visits pairs of product states, one of each side, and is refused (InputError)
    beyond ``max_states`` pairs: it is the bigger of the two products, or more."""
    fa, fb = _flags(a), _flags(b)
    if set(fa) != set(fb):
        only = sorted(set(fa) ^ set(fb))
        return Difference(events=tuple(only), reason="events in only one set: %s" % ", ".join("EV_" + e for e in only))
    for name in sorted(fa):
        if fa[name] != fb[name]:
            what = "controllable" if fa[name][0] != fb[name][0] else "public"
            return Difference(events=(name,), reason="EV_%s is %s in one set only" % (name, what))
    # Same names, and canonical models sort them: the event indices agree.
    ca, cb = Conjunction.of(a), Conjunction.of(b)
    budget = Budget(a.source, max_states, "the walk of both conjunctions (this set's and %s's)" % b.source)
    start = (ca.start, cb.start)
    seen: Dict[Tuple[Vector, Vector], Optional[tuple]] = {start: None}
    queue = deque([start])
    while queue:
        pair = queue.popleft()
        enabled_a, enabled_b = ca.enabled(pair[0]), cb.enabled(pair[1])
        if enabled_a != enabled_b:
            event = next(events_of(enabled_a ^ enabled_b))
            return Difference(word=tuple(a.events[e] for e in _word(seen, pair) + [event]),
                              allowed_by="A" if enabled_a >> event & 1 else "B",
                              reason="the conjunctions' languages differ")
        for (event, na), (_, nb) in zip(ca.moves(pair[0]), cb.moves(pair[1])):
            if (na, nb) not in seen:
                seen[(na, nb)] = (pair, event)
                queue.append((na, nb))
        budget.check(len(seen))
    return None


def _word(seen: Dict[Tuple[Vector, Vector], Optional[tuple]], pair) -> List[int]:
    out = []
    step = seen[pair]
    while step is not None:
        pair, event = step
        out.append(event)
        step = seen[pair]
    return out[::-1]


def format_difference(a: str, b: str, difference: Optional[Difference]) -> str:
    """The verdict of ``swarmvm equiv`` in one or two lines (the file names escaped to one line each)."""
    a, b = terminal(a), terminal(b)
    if difference is None:
        return "equivalent: %s and %s (same events, same language of the conjunction)" % (a, b)
    if not difference.word:
        return "not equivalent: %s" % difference.reason
    side, other = (a, b) if difference.allowed_by == "A" else (b, a)
    return "not equivalent: %s\nshortest distinguishing sequence: %s (allowed by %s, not by %s)" % (
        difference.reason, " ".join("EV_" + e for e in difference.word), side, other)
