"""Design checks on a supervisor set, read from the product of its local supervisors (the
conjunction; :mod:`swarmvm.models.product`). Each finding carries a shortest event sequence that
reaches it, so the designer can replay it with ``swarmvm trace``. Definitions (docs/models.md):

- **deadlock**: a reachable product state where no event at all can occur;
- **no control again**: a reachable state from which no controllable event can ever fire
  again, whatever happens (no state reachable from it enables one);
- **never occurs**: an event of the set that labels no reachable product transition;
- **ignored input**: a reachable state and an uncontrollable event that some supervisor
  holding the event allows there while another supervisor holding it has no transition: if
  it occurs, the VM must leave that supervisor where it is and count a model violation;
- **not confluent**: a reachable state with two enabled controllable events a and b where the
  choice matters: after a, b is not enabled, or after b, a is not, or a-then-b and b-then-a
  end in different states. Where every such pair commutes, the policy's choice only reorders
  events and cannot change where the robot ends up."""

from dataclasses import dataclass
from typing import Iterable, List, Set, Tuple

from ..boundary.escape import terminal
from ..compiler.model import Model
from .product import DEFAULT_MAX_STATES, Conjunction, Product, build_product, events_of


@dataclass(frozen=True)
class Finding:
    check: str
    detail: str
    word: Tuple[str, ...]        # shortest event sequence to the state concerned


@dataclass(frozen=True)
class Report:
    states: int
    findings: Tuple[Finding, ...]

    def of(self, check: str) -> List[Finding]:
        return [f for f in self.findings if f.check == check]


CHECKS = ("deadlock", "no control again", "never occurs", "ignored input", "not confluent")


def _names(model: Model, events: Iterable[int]) -> Tuple[str, ...]:
    return tuple(model.events[e] for e in events)


def _no_control_again(model: Model, product: Product) -> List[int]:
    """States from which no state enabling a controllable event is reachable."""
    can = {q for q, row in enumerate(product.edges) if any(model.controllable[e] for e, _ in row)}
    predecessors: list[list[int]] = [[] for _ in product.vectors]
    for q, row in enumerate(product.edges):
        for _, t in row:
            predecessors[t].append(q)
    stack = list(can)
    while stack:
        for p in predecessors[stack.pop()]:
            if p not in can:
                can.add(p)
                stack.append(p)
    return [q for q in range(len(product.vectors)) if q not in can]


def _ignored_inputs(model: Model, product: Product) -> List[Finding]:
    """One finding per (event, supervisor), at the first state: an uncontrollable event some
    holder offers there and the product does not enable."""
    conjunction = Conjunction.of(model)
    uncontrollable = sum(1 << e for e, c in enumerate(model.controllable) if not c)
    out, seen = [], set()
    for q, vector in enumerate(product.vectors):
        ignored = conjunction.offered(vector) & ~conjunction.enabled(vector) & uncontrollable
        for event in events_of(ignored):
            holders = conjunction.holders[event]
            defined = [s for s in holders if event in conjunction.delta[s][vector[s]]]
            for s in holders:
                if s not in defined and (event, s) not in seen:
                    seen.add((event, s))
                    out.append(Finding("ignored input", "EV_%s: supervisor %d has no transition in state %d (supervisor %d has)"
                                       % (model.events[event], s, vector[s], defined[0]), _names(model, product.word(q))))
    return out


def _local_conflicts(model: Model) -> List[List[List[Tuple[int, int]]]]:
    """Per supervisor and local state, the pairs (a, b), a < b, of controllable events it has
    transitions on whose local diamond fails: b undefined after a, a after b, or the two orders
    ending in different states. A product state enabling a and b is not confluent for them
    exactly when a supervisor holding both has the pair in its local state (a supervisor holding
    one of them moves the same in either order), so the product is searched for these pairs
    only, not for every pair of enabled events in every state."""
    out = []
    for sup in model.supervisors:
        delta = [{e: t for e, t, _ in row} for row in sup.states]
        conflicts = []
        for moves in delta:
            mine = sorted(e for e in moves if model.controllable[e])
            conflicts.append([(a, b) for i, a in enumerate(mine) for b in mine[i + 1:]
                              if delta[moves[a]].get(b) is None or delta[moves[a]].get(b) != delta[moves[b]].get(a)])
        out.append(conflicts)
    return out


def _not_confluent(model: Model, product: Product) -> List[Finding]:
    """One finding per pair of events, at the first (breadth-first: nearest) state."""
    conflicts = _local_conflicts(model)
    out: List[Finding] = []
    seen: Set[Tuple[int, int]] = set()
    for q, vector in enumerate(product.vectors):
        candidates = {pair for s, local in enumerate(vector) for pair in conflicts[s][local]} - seen
        after = {e: dict(product.edges[t]) for e, t in product.edges[q] if model.controllable[e]} if candidates else {}
        for a, b in sorted(pair for pair in candidates if pair[0] in after and pair[1] in after):
            ab, ba = after[a].get(b), after[b].get(a)
            if ab is None or ba is None:
                first, second = (a, b) if ab is None else (b, a)
                why = "EV_%s disables EV_%s" % (model.events[first], model.events[second])
            else:
                why = "the two orders end in different states"
            seen.add((a, b))
            out.append(Finding("not confluent", "EV_%s or EV_%s: %s" % (model.events[a], model.events[b], why),
                               _names(model, product.word(q))))
    return out


def check_properties(model: Model, max_states: int = DEFAULT_MAX_STATES) -> Report:
    """Every check of this module on ``model``'s product; InputError when the product is over
    the budget of ``max_states`` (:class:`swarmvm.models.product.Budget`), before any check runs."""
    product = build_product(model, max_states)
    findings = [Finding("deadlock", "no event can occur in product state (%s)" % ",".join(map(str, product.vectors[q])),
                        _names(model, product.word(q)))
                for q, row in enumerate(product.edges) if not row]
    findings += [Finding("no control again", "from product state (%s) no controllable event can fire again"
                         % ",".join(map(str, product.vectors[q])), _names(model, product.word(q)))
                 for q in _no_control_again(model, product)]
    used = {e for row in product.edges for e, _ in row}
    findings += [Finding("never occurs", "EV_%s labels no reachable transition of the product" % model.events[e], ())
                 for e in range(len(model.events)) if e not in used]
    findings += _ignored_inputs(model, product)
    findings += _not_confluent(model, product)
    return Report(len(product.vectors), tuple(findings))


def format_report(name: str, report: Report, examples: int | None = 3) -> str:
    """The report as Markdown: per check, the number of findings and the first ``examples``
    (every one when None), each with the shortest event sequence that reaches it; a cut list
    ends with how many are left out."""
    lines = ["## %s: product of %d state(s)" % (terminal(name), report.states)]     # a name is one line
    for check in CHECKS:
        found = report.of(check)
        lines.append("- %s: %s" % (check, "none" if not found else len(found)))
        for finding in found[:examples]:
            after = " after %s" % " ".join("EV_" + e for e in finding.word) if finding.word else ""
            lines.append("  - %s%s" % (finding.detail, after))
        if examples is not None and len(found) > examples:
            lines.append("  - ... and %d more (check --properties --all lists them)" % (len(found) - examples))
    return "\n".join(lines) + "\n"
