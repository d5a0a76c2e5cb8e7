"""Load and validate a compiled supervisor in Nadzoru 2's ``supervisor.yaml`` layout.

The file is parsed with PyYAML's BaseLoader, which leaves every scalar a string: YAML 1.1
would otherwise turn an event called ``on`` into True and ``010`` into 8. Each value is then
typed by the key and position it appears at, and every defect is reported as one
:class:`~swarmvm.boundary.errors.InputError` naming file, key and supervisor / state / event.
"""

import builtins
import hashlib
import os
import re
from collections.abc import Hashable, Mapping, Sequence
from fractions import Fraction
from typing import NoReturn, Optional

import yaml

from ..boundary.errors import InputError, ascii_int, decode_text, read_input
from ..compiler.model import LocalSupervisor, Supervisors, Transition
from ..compiler.runtime_files import image_format

REQUIRED = ("num_events", "num_supervisors", "events", "ev_controllable", "sup_events",
            "sup_init_state", "sup_data_pos", "sup_data")
OPTIONAL = ("sup_current_state", "ev_shared", "ev_public", "sup_data_prob_pos", "sup_data_prob")
# An event name: the image format's name bytes (swarmvm_format.NAME_CHARS), at most its
# MAX_NAME_LENGTH (255) of them.
NAME = re.compile(r"[A-Za-z0-9_]{0,%d}\Z" % image_format().MAX_NAME_LENGTH)
# An event name as the published VMs take it (exact mode, `swarmvm pack`): any visible ASCII, at
# most MAX_NAME_LENGTH characters (the source section keeps it as written).
WRITTEN = re.compile(r"[\x21-\x7e]{1,%d}\Z" % image_format().MAX_NAME_LENGTH)
INTEGER = re.compile(r"[0-9]+\Z")
# A probability as the tools write it: a decimal (an exponent of at most two digits) or a ratio.
PROBABILITY = re.compile(r"[0-9]{1,30}(\.[0-9]{0,30})?([eE][-+]?[0-9]{1,2})?\Z|[0-9]{1,30}/[0-9]{1,30}\Z")


class DuplicateKey(yaml.YAMLError):
    """A mapping gives ``key`` twice: at line ``first``, again at line ``line`` (1-based)."""

    def __init__(self, key: str, line: int, first: int) -> None:
        super().__init__("key %r given twice" % key)
        self.key, self.line, self.first = key, line, first


class _NoAliasLoader(yaml.BaseLoader):
    """YAML with every scalar a string, no aliases and no key given twice: a supervisor file
    never needs an alias, and nested aliases ("billion laughs") would make a small file expand
    to an enormous one; a second value for a key would otherwise silently replace the first."""

    def compose_node(self, parent: Optional[yaml.Node], index: int) -> Optional[yaml.Node]:
        if self.check_event(yaml.AliasEvent):
            # types-PyYAML leaves Parser.peek_event unannotated; "unused-ignore" while mypy's
            # configuration does not yet ask for typed calls here (pyproject.toml).
            mark = self.peek_event().start_mark  # type: ignore[no-untyped-call, unused-ignore]
            raise yaml.composer.ComposerError(None, None, "aliases (*name) are not accepted", mark)
        return super().compose_node(parent, index)

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> dict[Hashable, object]:
        """The mapping, once no scalar key of it comes twice (every scalar is a string here, so
        ``a`` and ``"a"`` are the same key); DuplicateKey otherwise. A list or mapping as a key
        is PyYAML's own error (unhashable)."""
        first_line: dict[str, int] = {}
        for key_node, _ in node.value:
            if isinstance(key_node, yaml.ScalarNode):
                line = key_node.start_mark.line + 1
                if key_node.value in first_line:
                    raise DuplicateKey(key_node.value, line, first_line[key_node.value])
                first_line[key_node.value] = line
        return super().construct_mapping(node, deep)


def probability(text: object) -> Optional[Fraction]:
    """``text`` as an exact probability in [0, 1], else None. The form is checked first:
    ``Fraction`` takes '1e-100000000' (minutes of arithmetic) and '1/0' (ZeroDivisionError)."""
    if not isinstance(text, str) or not PROBABILITY.match(text.strip()):
        return None
    try:
        value = Fraction(text.strip())
    except ZeroDivisionError:
        return None
    return value if 0 <= value <= 1 else None


def bare_name(raw: str) -> str:
    """The event name without Nadzoru's ``EV_`` prefix."""
    return raw[3:] if raw.startswith("EV_") else raw


def swarmvm_name(raw: str) -> str:
    """swarmvm's name for an event the published VMs accept (:data:`WRITTEN`): the bare name
    with each character other than a letter, digit or '_' made '_' (``EV_go-on`` is ``go_on``)."""
    return re.sub(r"[^A-Za-z0-9_]", "_", bare_name(raw))


class _Reader:
    """Typed access to the parsed document, raising InputError at the first defect."""

    def __init__(self, path: str, doc: dict[str, object]) -> None:
        self.path, self.doc = path, doc

    def fail(self, key: str, message: str, where: str = "") -> NoReturn:
        raise InputError(self.path, key, message, where)

    def int(self, value: object, key: str, where: str = "", low: int = 0, high: Optional[int] = None) -> int:
        """The non-negative integer ``value`` spells, in low..high when ``high`` is given (digits
        never spell a number under 0, so ``low`` is only checked with it)."""
        if not isinstance(value, str) or not INTEGER.match(value):
            self.fail(key, "expected a non-negative integer, got %s" % show_value(value), where)
        number: Optional[int] = ascii_int(value.lstrip("0") or "0")
        if number is None:
            self.fail(key, "value of %d digits out of range" % len(value), where)
        if high is not None and not low <= number <= high:
            self.fail(key, "value %d out of range (must be in %d..%d)" % (number, low, high), where)
        return number

    # (``int`` and ``list`` name the methods above in the class body: the builtins are spelled out.)
    def list(self, key: str, length: Optional[builtins.int] = None, what: str = "") -> builtins.list[object]:
        value = self.doc[key]
        if not isinstance(value, list):
            self.fail(key, "expected a list, got %s" % show_value(value))
        if length is not None and len(value) != length:
            self.fail(key, "has %d entries, %s says %d" % (len(value), what, length))
        return value

    def flags(self, key: str, length: builtins.int, names: Sequence[str]) -> builtins.list[bool]:
        values = self.list(key, length, "num_events")
        out = []
        for i, value in enumerate(values):
            if value not in ("0", "1"):
                self.fail("%s[%d]" % (key, i), "value %s is not 0 or 1" % show_value(value), "event EV_%s" % names[i])
            out.append(value == "1")
        return out


def show_value(value: object) -> str:
    """A value for a one-line message: quoted and escaped when empty, holding white space or
    unprintable or non-ASCII characters; cut at 60 characters."""
    if isinstance(value, str):
        plain = value and value.isascii() and value.isprintable() and not any(c.isspace() for c in value)
        shown = value if plain else ascii(value)
        return shown if len(shown) <= 60 else shown[:57] + "..."
    return "a list" if isinstance(value, list) else "a mapping" if isinstance(value, dict) else repr(value)


def load_supervisor(path: str, published: bool = False) -> Supervisors:
    """Read ``path`` and return :class:`Supervisors`, or raise InputError. ``published``: take
    what the published VMs run (docs/compat.md): event names of any visible ASCII characters
    (named by :func:`swarmvm_name`), and a state's second transition on an event dropped with a
    warning (their search finds the first); otherwise both are refused."""
    name = path
    raw = read_input(path)
    text = decode_text(path, raw)
    try:
        doc = yaml.load(text, Loader=_NoAliasLoader)
    except RecursionError:
        raise InputError(name, "", "not a supervisor: lists or mappings nested too deeply")
    except DuplicateKey as exc:
        raise InputError(name, show_value(exc.key), "key given twice (first at line %d); a YAML mapping holds each key once"
                         % exc.first, "line %d" % exc.line)
    except yaml.reader.ReaderError as exc:     # its own message takes two lines
        raise InputError(name, "", "not valid YAML at line %d: character #x%04x is not allowed"
                         % (text.count("\n", 0, exc.position) + 1, exc.character))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = " at line %d" % (mark.line + 1) if mark is not None else ""
        raise InputError(name, "", "not valid YAML%s: %s" % (line, getattr(exc, "problem", None) or exc))
    if not isinstance(doc, dict):
        raise InputError(name, "", "expected a mapping of keys at the top level, got %s" % show_value(doc))
    spec = supervisor_from_document(name, doc, published)
    spec.size_bytes = len(raw)
    spec.digest = hashlib.sha256(raw).digest()
    return spec


def supervisor_from_document(path: str, doc: dict[str, object], published: bool) -> Supervisors:
    """The supervisor set a parsed document spells, every scalar a string as BaseLoader gives
    it, checked key by key (InputError naming ``path``): the YAML and the C tables
    (:mod:`.nadzoru_c`) are validated by this one function."""
    spec = _parse(_Reader(path, doc), published)
    spec.file_order = True
    return spec


def _parse(r: _Reader, published: bool) -> Supervisors:
    doc = r.doc
    for key in REQUIRED:
        if key not in doc:
            r.fail(key, "missing key")
    # Unknown keys are tolerated (newer Nadzoru exports may add some) but reported.
    warnings = ["%s: %s: unknown key ignored" % (r.path, key) for key in doc if key not in REQUIRED + OPTIONAL]
    image = image_format()
    n_events = r.int(doc["num_events"], "num_events", low=1, high=image.MAX_EVENTS)
    n_sups = r.int(doc["num_supervisors"], "num_supervisors", low=1, high=image.MAX_SUPERVISORS)

    events: list[str] = []
    seen: dict[str, int] = {}
    written: list[str] = []
    for i, raw in enumerate(r.list("events", n_events, "num_events")):
        if published and isinstance(raw, str) and WRITTEN.match(raw):
            bare = swarmvm_name(raw)
        elif not isinstance(raw, str) or not NAME.match(bare_name(raw)):
            r.fail("events[%d]" % i, "%s is not an event name (at most %d letters, digits and '_')"
                   % (show_value(raw), image.MAX_NAME_LENGTH))
        else:
            bare = bare_name(raw)
        if bare in seen:
            r.fail("events[%d]" % i, "duplicate event name (also events[%d])" % seen[bare], "event EV_%s" % bare)
        seen[bare] = i
        events.append(bare)
        written.append(raw)

    controllable = r.flags("ev_controllable", n_events, events)
    public = [False] * n_events
    for key in ("ev_shared", "ev_public"):
        if key in doc:
            flags = r.flags(key, n_events, events)
            if "ev_shared" in doc and key == "ev_public" and flags != public:
                i = next(i for i in range(n_events) if flags[i] != public[i])
                r.fail("ev_public[%d]" % i, "disagrees with ev_shared[%d]" % i, "event EV_%s" % events[i])
            public = flags

    alphabets: list[frozenset[str]] = []
    rows = r.list("sup_events", n_sups, "num_supervisors")
    for s, row in enumerate(rows):
        if not isinstance(row, list) or len(row) != n_events:
            r.fail("sup_events[%d]" % s, "expected a list of %d flags (num_events)" % n_events, "supervisor %d" % s)
        for e, value in enumerate(row):
            if value not in ("0", "1"):
                r.fail("sup_events[%d][%d]" % (s, e), "value %s is not 0 or 1" % show_value(value),
                       "supervisor %d, event EV_%s" % (s, events[e]))
        alphabets.append(frozenset(events[e] for e in range(n_events) if row[e] == "1"))

    positions = [r.int(v, "sup_data_pos[%d]" % s, "supervisor %d" % s)
                 for s, v in enumerate(r.list("sup_data_pos", n_sups, "num_supervisors"))]
    data = r.list("sup_data")
    index = {name: i for i, name in enumerate(events)}
    # published: sup_data names an event as the events list writes it, or as swarmvm names it
    as_written = dict(zip(written, events)) if published else None
    supervisors: list[list[list[Transition]]] = []
    for s in range(n_sups):
        end = positions[s + 1] if s + 1 < n_sups else len(data)
        states = _parse_block(r, data, positions[s], end, s, index, alphabets[s], as_written, warnings)
        supervisors.append(states)

    inits = r.list("sup_init_state", n_sups, "num_supervisors")
    initial = [r.int(v, "sup_init_state[%d]" % s, "supervisor %d" % s, high=len(supervisors[s]) - 1)
               for s, v in enumerate(inits)]
    current = list(initial)
    if "sup_current_state" in doc:
        current = [r.int(v, "sup_current_state[%d]" % s, "supervisor %d" % s, high=len(supervisors[s]) - 1)
                   for s, v in enumerate(r.list("sup_current_state", n_sups, "num_supervisors"))]

    probabilistic = "sup_data_prob" in doc or "sup_data_prob_pos" in doc
    if probabilistic:
        for key in ("sup_data_prob", "sup_data_prob_pos"):
            if key not in doc:
                r.fail(key, "missing key (the probabilistic keys come in a pair)")
        _parse_probabilities(r, supervisors, controllable, index, n_sups)

    return Supervisors(
        source=os.path.basename(r.path), events=events,
        controllable=dict(zip(events, controllable)), public=dict(zip(events, public)),
        supervisors=[LocalSupervisor(alphabets[s], initial[s], supervisors[s]) for s in range(n_sups)],
        probabilistic=probabilistic, warnings=warnings, written=written, current=current)


def _parse_block(r: _Reader, data: Sequence[object], start: int, end: int, s: int, index: Mapping[str, int],
                 alphabet: frozenset[str], as_written: Optional[Mapping[str, str]],
                 warnings: list[str]) -> list[list[Transition]]:
    """One supervisor's states from ``sup_data[start:end]``: n, then n (event, hi, lo).
    ``as_written`` (published mode: the events' names as written -> swarmvm's): names are looked
    up in it first, and a second transition on an event from a state is dropped, with a
    warning added to ``warnings``, rather than refused."""
    if not 0 <= start <= end <= len(data):
        r.fail("sup_data_pos[%d]" % s, "position %d does not start a block inside sup_data (%d entries)"
               % (start, len(data)), "supervisor %d" % s)
    states: list[list[Transition]] = []
    targets: list[tuple[int, str, int]] = []
    pos = start
    while pos < end:
        q = len(states)
        where = "supervisor %d, state %d" % (s, q)
        count = r.int(data[pos], "sup_data[%d]" % pos, where)
        if pos + 1 + 3 * count > end:
            r.fail("sup_data_pos[%d]" % (s + 1) if end != len(data) else "sup_data",
                   "the block of supervisor %d does not end where %s" % (
                       s, "the next supervisor starts (sup_data[%d])" % end if end != len(data) else "sup_data ends"),
                   where)
        transitions: list[Transition] = []
        seen: set[str] = set()
        for k in range(count):
            p = pos + 1 + 3 * k
            raw = data[p]
            if as_written is not None and isinstance(raw, str) and raw in as_written:
                name = as_written[raw]
            elif not isinstance(raw, str) or not NAME.match(bare_name(raw)):
                r.fail("sup_data[%d]" % p, "%s is not an event name" % show_value(raw), where)
            else:
                name = bare_name(raw)
            at = "%s, event EV_%s" % (where, name)
            if name not in index:
                r.fail("sup_data[%d]" % p, "event is not in events", at)
            if name not in alphabet:
                r.fail("sup_data[%d]" % p, "event is not in the supervisor's alphabet (sup_events)", at)
            if name in seen and as_written is None:
                r.fail("sup_data[%d]" % p, "nondeterministic: a second transition on this event from this state", at)
            hi = r.int(data[p + 1], "sup_data[%d]" % (p + 1), at, high=255)
            lo = r.int(data[p + 2], "sup_data[%d]" % (p + 2), at, high=255)
            targets.append((p + 1, at, hi * 256 + lo))
            if name in seen:
                warnings.append("%s: sup_data[%d]: %s: a second transition on this event from this state; the first is "
                                "kept, as the published VMs' search finds it" % (r.path, p, at))
                continue
            seen.add(name)
            transitions.append(Transition(name, hi * 256 + lo))
        states.append(transitions)
        pos += 1 + 3 * count
    if not states:
        r.fail("sup_data_pos[%d]" % s, "supervisor has no states", "supervisor %d" % s)
    for p, at, target in targets:
        if target >= len(states):
            r.fail("sup_data[%d]" % p, "target %d out of range (the supervisor has %d states)" % (target, len(states)), at)
    return states


def _parse_probabilities(r: _Reader, supervisors: Sequence[Sequence[Sequence[Transition]]],
                         controllable: Sequence[bool], index: Mapping[str, int], n_sups: int) -> None:
    """Nadzoru 2's probabilistic keys: per state ``k, p_1..p_k`` for its k controllable
    out-transitions in sup_data order. Probabilities are read exactly (as fractions). A position
    past the end of sup_data_prob is refused: a block runs to the next position, read entry by entry."""
    data = r.list("sup_data_prob")
    positions = [r.int(v, "sup_data_prob_pos[%d]" % s, "supervisor %d" % s, high=len(data))
                 for s, v in enumerate(r.list("sup_data_prob_pos", n_sups, "num_supervisors"))]
    for s, states in enumerate(supervisors):
        pos = positions[s]
        end = positions[s + 1] if s + 1 < n_sups else len(data)
        for q, transitions in enumerate(states):
            where = "supervisor %d, state %d" % (s, q)
            if pos >= end:
                r.fail("sup_data_prob", "block ends before the supervisor's last state", where)
            wanted = [t for t in transitions if controllable[index[t.event]]]
            count = r.int(data[pos], "sup_data_prob[%d]" % pos, where)
            if count != len(wanted):
                r.fail("sup_data_prob[%d]" % pos, "%d probabilities, the state has %d controllable transitions"
                       % (count, len(wanted)), where)
            for k, t in enumerate(wanted):
                p = pos + 1 + k
                at = "%s, event EV_%s" % (where, t.event)
                if p >= end:
                    r.fail("sup_data_prob", "block ends inside a state's probabilities", at)
                value = probability(data[p])
                if value is None:
                    r.fail("sup_data_prob[%d]" % p, "%s is not a probability in [0, 1]" % show_value(data[p]), at)
                t.probability = value
            pos += 1 + count
        if pos != end:
            r.fail("sup_data_prob_pos[%d]" % (s + 1) if s + 1 < n_sups else "sup_data_prob",
                   "the probability block of supervisor %d does not end where the next starts" % s,
                   "supervisor %d" % s)
