"""Read an IDES 2.x model (``.xmd``): ``<model type="FSA"><data>`` with ``<state>``, ``<event>``
and ``<transition>`` elements; a state's or event's flags are empty elements inside its
``<properties>`` (``<initial/>``, ``<marked/>``, ``<controllable/>``), its name is ``<name>``.

IDES has no public flag (every event is private) and allows a transition without an event,
which swarmvm refuses: a supervisor has no silent moves. Layout (``<meta>``) is ignored."""

from xml.etree.ElementTree import Element

from ..boundary.errors import InputError
from .automaton import AutomatonBuilder, AutomatonFile, read_fsa_xml


def _properties(element: Element) -> set[str]:
    props = element.find("properties")
    return set() if props is None else {child.tag for child in props}


def _id(path: str, element: Element, attribute: str, key: str) -> str:
    value = (element.get(attribute) or "").strip()
    if not value:
        raise InputError(path, key, "missing attribute %s" % attribute)
    return value


def read_xmd(path: str) -> AutomatonFile:
    """One IDES ``.xmd`` file -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
    data, size = read_fsa_xml(path)
    build = AutomatonBuilder(path)
    for element in data.findall("state"):
        props = _properties(element)
        build.state(_id(path, element, "id", "state"), "initial" in props, "marked" in props)
    for element in data.findall("event"):
        name = (element.findtext("name") or "").strip()
        build.event(_id(path, element, "id", "event"), name, "controllable" in _properties(element))
    for element in data.findall("transition"):
        source = _id(path, element, "source", "transition")
        if element.get("event") is None:
            raise InputError(path, "transition", "a transition without an event is not supported",
                             "transition %s" % element.get("id", "?"))
        build.transition(source, element.get("event", "").strip(), _id(path, element, "target", "transition"))
    return build.build(size)
