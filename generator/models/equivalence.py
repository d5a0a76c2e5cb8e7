"""Are two supervisor sets the same controller? Same events (names, controllable, public) and
the same language of their conjunctions (closed languages: every state marked, as the VM runs
them), whatever their state numbering or their split into local supervisors.

The languages are compared by a breadth-first walk of the pair product, over the events of
both sets: the first pair of states where one side allows an event the other does not gives a
shortest distinguishing event sequence, whether or not the event sets differ."""

from collections import deque
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

from ..boundary.escape import terminal
from ..compiler.model import Model
from .product import DEFAULT_MAX_STATES, Budget, Conjunction, Vector, events_of

Pair = Tuple[Vector, Vector]    # a state of both conjunctions walked side by side
# Each pair reached -> the pair and event it was first reached from (None: the start).
Seen = Dict[Pair, Optional[Tuple[Pair, int]]]


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


def _conjunction(model: Model, names: Sequence[str]) -> Conjunction:
    """``model``'s conjunction over the events ``names`` (sorted, holding the model's): an event
    the model does not have is never enabled (a supervisor with no transition holds it), so
    the language stays the model's own, over the larger alphabet."""
    index = {name: i for i, name in enumerate(names)}
    renumber = [index[name] for name in model.events]
    alphabets = [frozenset(renumber[e] for e in sup.alphabet) for sup in model.supervisors]
    delta = [[{renumber[e]: t for e, t, _ in row} for row in sup.states] for sup in model.supervisors]
    missing = frozenset(range(len(names))) - frozenset(renumber)
    if missing:
        alphabets, delta = alphabets + [missing], delta + [[{}]]
    return Conjunction(len(names), alphabets, delta, tuple(0 for _ in alphabets))


def _event_difference(a: Model, b: Model) -> Optional[Difference]:
    """How the two sets' events differ (names, then flags), without a word yet; None if alike."""
    fa, fb = _flags(a), _flags(b)
    if set(fa) != set(fb):
        only = sorted(set(fa) ^ set(fb))
        return Difference(events=tuple(only), reason="events in only one set: %s" % ", ".join("EV_" + e for e in only))
    for name in sorted(fa):
        if fa[name] != fb[name]:
            what = "controllable" if fa[name][0] != fb[name][0] else "public"
            return Difference(events=(name,), reason="EV_%s is %s in one set only" % (name, what))
    return None


def compare(a: Model, b: Model, max_states: int = DEFAULT_MAX_STATES) -> Optional[Difference]:
    """None when ``a`` and ``b`` are equivalent, else a :class:`Difference`: how the events
    differ, if they do, and a shortest word one conjunction accepts and the other does not,
    whenever one exists (the languages are compared over both sets' events together, so an
    event of one set only distinguishes them as soon as it can occur). The walk visits pairs of
    product states, one of each side, and is refused (InputError) beyond ``max_states`` pairs:
    it is the bigger of the two products, or more."""
    events = _event_difference(a, b)
    names = sorted(set(a.events) | set(b.events))
    ca, cb = _conjunction(a, names), _conjunction(b, names)
    budget = Budget(a.source, max_states, "the walk of both conjunctions (this set's and %s's)" % b.source)
    start = (ca.start, cb.start)
    seen: Seen = {start: None}
    queue = deque([start])
    while queue:
        pair = queue.popleft()
        enabled_a, enabled_b = ca.enabled(pair[0]), cb.enabled(pair[1])
        if enabled_a != enabled_b:
            event = next(events_of(enabled_a ^ enabled_b))
            return Difference(events=events.events if events else (),
                              word=tuple(names[e] for e in _word(seen, pair) + [event]),
                              allowed_by="A" if enabled_a >> event & 1 else "B",
                              reason=events.reason if events else "the conjunctions' languages differ")
        for (event, na), (_, nb) in zip(ca.moves(pair[0]), cb.moves(pair[1])):
            if (na, nb) not in seen:
                seen[(na, nb)] = (pair, event)
                queue.append((na, nb))
        budget.check(len(seen))
    return events


def _word(seen: Seen, pair: Pair) -> List[int]:
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
        return "not equivalent: %s (the conjunctions' languages are the same: no event sequence tells them apart)" % (
            difference.reason)
    side, other = (a, b) if difference.allowed_by == "A" else (b, a)
    return "not equivalent: %s\nshortest distinguishing sequence: %s (allowed by %s, not by %s)" % (
        difference.reason, " ".join("EV_" + e for e in difference.word), side, other)
