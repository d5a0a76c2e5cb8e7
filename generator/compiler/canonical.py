"""Canonical form: what makes two exports of the same supervisors compile to the same bytes.

Events are sorted by name and identified by their index in that order. Each supervisor's
states are renumbered breadth-first from its initial state (which becomes 0), following
transitions in event order, then from the input's current state if that is not reached (a
supervisor.yaml's sup_current_state, where the published VMs start); states not reached are
dropped, with a warning. Supervisors keep
the order of the input."""

from collections import deque

from .model import CanonicalSupervisor, Model, Supervisors

SHOWN_STATES = 20    # unreachable states named in the warning; a range of thousands would be a line of 400 kB


def canonicalise(spec: Supervisors) -> Model:
    """:class:`~swarmvm.compiler.model.Supervisors` -> :class:`~swarmvm.compiler.model.Model`."""
    events = tuple(sorted(spec.events))
    index = {name: i for i, name in enumerate(events)}
    supervisors: list[CanonicalSupervisor] = []
    warnings = list(spec.warnings)
    for s, local in enumerate(spec.supervisors):
        rows = [sorted((index[t.event], t.target, t.probability) for t in row) for row in local.states]
        number = {local.initial: 0}
        order = [local.initial]
        # The input's current state (a supervisor.yaml's sup_current_state, where the published
        # VMs start) is searched from too when the initial state does not reach it.
        current = spec.current[s] if len(spec.current) == len(spec.supervisors) else local.initial
        for start in (local.initial, current):
            if start not in number:
                number[start] = len(order)
                order.append(start)
            queue = deque([start])
            while queue:
                for _, target, _ in rows[queue.popleft()]:
                    if target not in number:
                        number[target] = len(order)
                        order.append(target)
                        queue.append(target)
        dropped = len(rows) - len(order)
        if dropped:
            missing = sorted(set(range(len(rows))) - set(number))
            shown = ", ".join(map(str, missing[:SHOWN_STATES])) + (", ..." if dropped > SHOWN_STATES else "")
            warnings.append("%s: supervisor %d: %d unreachable state(s) dropped (states %s)"
                            % (spec.source, s, dropped, shown))
        states = tuple(tuple((e, number[target], p) for e, target, p in rows[old]) for old in order)
        supervisors.append(CanonicalSupervisor(frozenset(index[n] for n in local.alphabet), states, tuple(order),
                                               number[current]))
    return Model(
        source=spec.source, events=events,
        controllable=tuple(spec.controllable[n] for n in events),
        public=tuple(spec.public[n] for n in events),
        supervisors=tuple(supervisors), probabilistic=spec.probabilistic, warnings=tuple(warnings))
