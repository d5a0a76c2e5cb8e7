"""One automaton read from one file, built through the checks every source format shares.

Every reader (Nadzoru 2 XML, IDES ``.xmd``, Nadzoru ``.nza``, libFAUDES ``.gen``) declares
states, events and transitions by the keys its format uses; :class:`AutomatonBuilder` turns
them into a :class:`~swarmvm.compiler.model.LocalSupervisor` and reports every defect (duplicate or
undeclared ids, a missing or second initial state, nondeterminism, bad event names) as the
same one-line :class:`~swarmvm.boundary.errors.InputError`, whatever the format."""

from dataclasses import dataclass
from fractions import Fraction
from typing import Dict, Hashable, List, NoReturn, Optional, Tuple
from xml.etree.ElementTree import Element, ParseError

import defusedxml.ElementTree as SafeET
from defusedxml import DefusedXmlException

from ..boundary.errors import InputError, read_input
from ..compiler.model import LocalSupervisor, Transition
from ..compiler.runtime_files import image_format
from .supervisor_yaml import NAME, show_value


@dataclass
class AutomatonFile:
    """What one file declares: its events {name: (controllable, public)} and its automaton."""
    events: Dict[str, Tuple[bool, bool]]
    supervisor: LocalSupervisor
    probabilistic: bool
    size_bytes: int


class AutomatonBuilder:
    """Collects one file's states, events and transitions, refusing what no format allows.

    ``key`` names the part of the file in error messages (an attribute or section name)."""

    def __init__(self, path: str) -> None:
        self.path = path
        self._states: Dict[Hashable, int] = {}
        self._initial: Optional[Hashable] = None
        self._marked: List[Optional[bool]] = []
        self._events: Dict[Hashable, str] = {}
        self._flags: Dict[str, Tuple[bool, bool]] = {}
        self._rows: List[List[Transition]] = []
        self.probabilistic = False

    def fail(self, key: str, message: str, where: str = "") -> NoReturn:
        raise InputError(self.path, key, message, where)

    def state(self, sid: Hashable, initial: bool, marked: Optional[bool] = None, key: str = "state") -> None:
        if sid in self._states:
            self.fail(key, "duplicate state id", "state %s" % sid)
        self._states[sid] = len(self._states)
        self._marked.append(marked)
        self._rows.append([])
        if initial:
            if self._initial is not None:
                self.fail(key, "a second initial state", "state %s" % sid)
            self._initial = sid

    def event(self, eid: Hashable, name: object, controllable: bool, public: bool = False, key: str = "event") -> None:
        if not isinstance(name, str) or not NAME.match(name):
            self.fail(key, "%s is not an event name (at most %d letters, digits and '_')"
                      % (ascii(name[:60]) if isinstance(name, str) else show_value(name),
                         image_format().MAX_NAME_LENGTH), "event %s" % eid)
        if name in self._flags:
            self.fail(key, "duplicate event name", "event EV_%s" % name)
        if eid in self._events:
            self.fail(key, "duplicate event id", "event EV_%s" % name)
        self._events[eid] = name
        self._flags[name] = (controllable, public)

    def transition(self, source: Hashable, eid: Hashable, target: Hashable,
                   probability: Optional[Fraction] = None, key: str = "transition") -> None:
        if eid not in self._events:
            self.fail(key, "event id %s is not declared" % (eid,), "state %s" % (source,))
        name = self._events[eid]
        where = "state %s, event EV_%s" % (source, name)
        for sid in (source, target):
            if sid not in self._states:
                self.fail(key, "state id %s is not declared" % (sid,), where)
        row = self._rows[self._states[source]]
        if any(t.event == name for t in row):
            self.fail(key, "nondeterministic: a second transition on this event", where)
        self.probabilistic = self.probabilistic or probability is not None
        row.append(Transition(name, self._states[target], probability))

    def build(self, size_bytes: int, key: str = "state") -> AutomatonFile:
        if not self._states:
            self.fail(key, "the automaton has no states")
        if self._initial is None:
            self.fail(key, "no initial state")
        marked = None
        if any(m is not None for m in self._marked):
            marked = frozenset(i for i, m in enumerate(self._marked) if m)
        supervisor = LocalSupervisor(frozenset(self._flags), self._states[self._initial], self._rows, marked)
        return AutomatonFile(dict(self._flags), supervisor, self.probabilistic, size_bytes)


def parse_xml(path: str, raw: bytes) -> Element:
    """Parse XML without expanding entities: a DOCTYPE, an entity or an external reference is
    refused (no billion laughs, no file inclusion). The encoding a declaration names is looked
    up among Python's codecs by expat: an unknown one (LookupError), a multi-byte or a non-text
    codec (ValueError, UnicodeError) is bad input too."""
    try:
        return SafeET.fromstring(raw, forbid_dtd=True, forbid_entities=True, forbid_external=True)
    except ParseError as exc:
        raise InputError(path, "", "not valid XML: %s" % exc)
    except DefusedXmlException:     # a ValueError: before the encoding's
        raise InputError(path, "", "a DOCTYPE or entity declaration is not accepted")
    except (LookupError, ValueError) as exc:
        raise InputError(path, "", "not valid XML: its encoding declaration cannot be used (%s)" % show_value(str(exc)))


def read_fsa_xml(path: str) -> Tuple[Element, int]:
    """The ``<data>`` element of an XML ``<model type="FSA">`` file and the file's size: the
    frame Nadzoru 2 and IDES share."""
    raw = read_input(path)
    root = parse_xml(path, raw)
    if root.tag != "model" or root.get("type") != "FSA":
        raise InputError(path, "model", "expected <model type=\"FSA\"> at the top, got <%s>" % root.tag)
    data = root.find("data")
    if data is None:
        raise InputError(path, "data", "missing <data> element")
    return data, len(raw)
