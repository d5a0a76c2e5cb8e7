"""Load source automata (Nadzoru 2 XML, ``<model type="FSA">``) as a set of local supervisors.

Each file is one local supervisor whose alphabet is the events it declares. Controllability
and the ``public`` flag must agree between files that share an event; a ``probability``
attribute on transitions makes the set probabilistic (as Nadzoru 2's probabilistic plug-in)."""

import os
import xml.etree.ElementTree as ET
from fractions import Fraction

from .errors import InputError, read_input
from .load_supervisor import NAME
from .model import LocalSupervisor, Supervisors, Transition

TRUE = {"true": True, "false": False}


def _flag(path, element, attribute, where, default=None):
    value = element.get(attribute)
    if value is None and default is not None:
        return default
    if value is None or value.strip().lower() not in TRUE:
        raise InputError(path, attribute, "expected True or False, got %r" % value, where)
    return TRUE[value.strip().lower()]


def _int_attr(path, element, attribute, where):
    value = element.get(attribute, "")
    if not value.isdigit():
        raise InputError(path, attribute, "expected a non-negative integer id, got %r" % value, where)
    return int(value)


def load_automaton(path):
    """One XML file -> (events {name: (controllable, public)}, LocalSupervisor, probabilistic, bytes)."""
    raw = read_input(path)
    try:
        root = ET.fromstring(raw)
    except ET.ParseError as exc:
        raise InputError(path, "", "not valid XML: %s" % exc)
    if root.tag != "model" or root.get("type") != "FSA":
        raise InputError(path, "model", "expected <model type=\"FSA\"> at the top, got <%s>" % root.tag)
    data = root.find("data")
    if data is None:
        raise InputError(path, "data", "missing <data> element")

    states = {}
    initial = None
    for element in data.findall("state"):
        sid = _int_attr(path, element, "id", "state")
        if sid in states:
            raise InputError(path, "state", "duplicate state id", "state %d" % sid)
        states[sid] = len(states)
        if _flag(path, element, "initial", "state %d" % sid):
            if initial is not None:
                raise InputError(path, "state", "a second initial state", "state %d" % sid)
            initial = sid
    if not states:
        raise InputError(path, "state", "the automaton has no states")
    if initial is None:
        raise InputError(path, "state", "no initial state")

    events, by_id = {}, {}
    for element in data.findall("event"):
        eid = _int_attr(path, element, "id", "event")
        name = element.get("name", "")
        if not NAME.match(name):
            raise InputError(path, "event", "%r is not an event name (letters, digits and '_')" % name, "event %d" % eid)
        if name in events:
            raise InputError(path, "event", "duplicate event name", "event EV_%s" % name)
        where = "event EV_%s" % name
        events[name] = (_flag(path, element, "controllable", where), _flag(path, element, "public", where, False))
        by_id[eid] = name

    table = [[] for _ in states]
    probabilistic = False
    for element in data.findall("transition"):
        source = _int_attr(path, element, "source", "transition")
        target = _int_attr(path, element, "target", "transition")
        eid = _int_attr(path, element, "event", "transition")
        if eid not in by_id:
            raise InputError(path, "transition", "event id %d is not declared" % eid, "state %d" % source)
        name = by_id[eid]
        where = "state %d, event EV_%s" % (source, name)
        for sid in (source, target):
            if sid not in states:
                raise InputError(path, "transition", "state id %d is not declared" % sid, where)
        row = table[states[source]]
        if any(t.event == name for t in row):
            raise InputError(path, "transition", "nondeterministic: a second transition on this event", where)
        probability = None
        if element.get("probability") is not None:
            probabilistic = True
            try:
                probability = Fraction(element.get("probability"))
            except ValueError:
                probability = None
            if probability is None or not 0 <= probability <= 1:
                raise InputError(path, "probability", "%r is not a probability in [0, 1]" % element.get("probability"), where)
        row.append(Transition(name, states[target], probability))
    return events, LocalSupervisor(frozenset(events), states[initial], table), probabilistic, len(raw)


def load_automata(paths):
    """Several XML files -> one :class:`Supervisors` (one local supervisor per file)."""
    events, supervisors, probabilistic, size = {}, [], False, 0
    for path in paths:
        declared, supervisor, prob, nbytes = load_automaton(path)
        for name, flags in declared.items():
            if name in events and events[name] != flags:
                what = "controllable" if events[name][0] != flags[0] else "public"
                raise InputError(path, what, "disagrees with an earlier file on this event", "event EV_%s" % name)
            events.setdefault(name, flags)
        supervisors.append(supervisor)
        probabilistic = probabilistic or prob
        size += nbytes
    if probabilistic:
        for supervisor in supervisors:
            for row in supervisor.states:
                for t in row:
                    if t.probability is None and events[t.event][0]:
                        t.probability = Fraction(1)
    names = list(events)
    return Supervisors(
        source="+".join(os.path.basename(p) for p in paths), events=names,
        controllable={n: events[n][0] for n in names}, public={n: events[n][1] for n in names},
        supervisors=supervisors, size_bytes=size, probabilistic=probabilistic)
