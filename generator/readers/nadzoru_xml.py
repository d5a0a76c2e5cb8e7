"""Read a Nadzoru 2 automaton (``.xml``): ``<model type="FSA"><data>`` with ``<state>``,
``<event>`` and ``<transition>`` elements, flags and ids as attributes; a ``probability``
attribute on a transition makes the automaton probabilistic (Nadzoru 2's probabilistic
plug-in)."""

from typing import Optional
from xml.etree.ElementTree import Element

from ..boundary.errors import InputError, ascii_int
from .automaton import AutomatonBuilder, AutomatonFile, read_fsa_xml
from .supervisor_yaml import NAME
from .supervisor_yaml import probability as parse_probability

TRUE = {"true": True, "false": False}


def _flag(path: str, element: Element, attribute: str, where: str, default: Optional[bool] = None) -> bool:
    value = element.get(attribute)
    if value is None and default is not None:
        return default
    if value is None or value.strip().lower() not in TRUE:
        raise InputError(path, attribute, "expected True or False, got %r" % value, where)
    return TRUE[value.strip().lower()]


def _int_attr(path: str, element: Element, attribute: str, where: str) -> int:
    value = element.get(attribute, "")
    number = ascii_int(value)
    if number is None:
        raise InputError(path, attribute, "expected a non-negative integer id of at most 9 digits, got %r" % value[:40],
                         where)
    return number


def read_nadzoru_xml(path: str) -> AutomatonFile:
    """One Nadzoru 2 XML file -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
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
