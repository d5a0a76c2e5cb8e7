"""Load source automata as a set of local supervisors: Nadzoru 2 XML (``<model type="FSA">``,
read here), IDES ``.xmd``, Nadzoru ``.nza`` and libFAUDES ``.gen`` (one reader module each).

Each file is one local supervisor whose alphabet is the events it declares. Controllability
and the ``public`` flag must agree between files that share an event; a ``probability``
attribute on transitions makes the set probabilistic (as Nadzoru 2's probabilistic plug-in)."""

import os
from fractions import Fraction

from .automaton import AutomatonBuilder, read_fsa_xml
from .errors import InputError, ascii_int
from .load_supervisor import NAME
from .load_supervisor import probability as parse_probability
from .model import Supervisors
from .read_gen import load_gen
from .read_nza import load_nza
from .read_xmd import load_xmd

SUFFIXES = (".xml", ".xmd", ".nza", ".gen")

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
    number = ascii_int(value)
    if number is None:
        raise InputError(path, attribute, "expected a non-negative integer id of at most 9 digits, got %r" % value[:40],
                         where)
    return number


def load_automaton(path):
    """One Nadzoru 2 XML file -> :class:`~swarmvm.automaton.AutomatonFile`."""
    data, size = read_fsa_xml(path)

    build = AutomatonBuilder(path)
    for element in data.findall("state"):
        sid = _int_attr(path, element, "id", "state")
        where = "state %d" % sid
        marked = _flag(path, element, "marked", where) if element.get("marked") is not None else None
        build.state(sid, _flag(path, element, "initial", where), marked)
    for element in data.findall("event"):
        eid = _int_attr(path, element, "id", "event")
        name = element.get("name", "")
        where = "event EV_%s" % name if NAME.match(name) else "event %d" % eid
        build.event(eid, name, _flag(path, element, "controllable", where), _flag(path, element, "public", where, False))
    for element in data.findall("transition"):
        source = _int_attr(path, element, "source", "transition")
        target = _int_attr(path, element, "target", "transition")
        eid = _int_attr(path, element, "event", "transition")
        probability = None
        text = element.get("probability")
        if text is not None:
            probability = parse_probability(text)
            if probability is None:
                raise InputError(path, "probability", "%r is not a probability in [0, 1]" % text[:40], "state %d" % source)
        build.transition(source, eid, target, probability)
    return build.build(size)


def read_automaton(path):
    """Any one-automaton file, by its extension -> :class:`~swarmvm.automaton.AutomatonFile`."""
    readers = {".xml": load_automaton, ".xmd": load_xmd, ".nza": load_nza, ".gen": load_gen}
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in readers:
        raise InputError(path, "", "not an automaton file (%s)" % ", ".join(SUFFIXES))
    return readers[suffix](path)


def load_automata(paths):
    """Several XML files -> one :class:`Supervisors` (one local supervisor per file)."""
    events: dict = {}
    supervisors: list = []
    probabilistic, size = False, 0
    for path in paths:
        read = read_automaton(path)
        for name, flags in read.events.items():
            if name in events and events[name] != flags:
                what = "controllable" if events[name][0] != flags[0] else "public"
                raise InputError(path, what, "disagrees with an earlier file on this event", "event EV_%s" % name)
            events.setdefault(name, flags)
        supervisors.append(read.supervisor)
        probabilistic = probabilistic or read.probabilistic
        size += read.size_bytes
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
