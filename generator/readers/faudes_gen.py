"""Read a libFAUDES generator in its token format (``.gen``)::

    <Generator name="G" ftype="System">
    <Alphabet> a +C+ b </Alphabet>                 % +C+ after an event: controllable
    <States> s1 s2 <Consecutive> 3 5 </Consecutive> </States>
    <TransRel> s1 a s2  s2 b s1 </TransRel>        % triples: source event target
    <InitStates> s1 </InitStates>
    <MarkedStates> s1 s2 </MarkedStates>
    </Generator>

``%`` starts a comment; names may be quoted; a number names a state by its index. Other
attribute flags (``+o+``, ``+F+``, ...) are accepted and ignored. libFAUDES has no public
flag; swarmvm writes its public events in a comment libFAUDES skips, ``% swarmvm public: a b``,
and reads it back (without it every event is private). Exactly one initial state is required
(a supervisor starts somewhere definite)."""

import re
from typing import Dict, List, Sequence, Tuple

from ..boundary.errors import InputError, ascii_int, decode_text, read_input
from ..compiler.runtime_files import image_format
from .automaton import AutomatonBuilder, AutomatonFile

TOKEN = re.compile(r"""
    (?P<space>\s+|%[^\n]*)
  | (?P<tag></?[A-Za-z]+(?:\s+[A-Za-z]+="[^"]*")*\s*/?>)
  | (?P<attr>\+[A-Za-z]*\+)
  | (?P<string>"[^"\n]*")
  | (?P<word>[^\s<>"%+]+)
""", re.VERBOSE)
SECTIONS = ("Alphabet", "States", "TransRel", "InitStates", "MarkedStates")
MAX_CONSECUTIVE = image_format().MAX_STATES + 1      # more states than any image can hold
PUBLIC = re.compile(r"^[ \t]*% swarmvm public:(.*)$", re.MULTILINE)
Token = Tuple[str, str, int]      # (kind, text, line)


def _tokens(path: str, text: str) -> List[Token]:
    out: List[Token] = []
    pos, line = 0, 1
    while pos < len(text):
        match = TOKEN.match(text, pos)
        if match is None:
            raise InputError(path, "", "unexpected character %r" % text[pos], "line %d" % line)
        kind, value = match.lastgroup or "", match.group()
        if kind == "string":
            kind, value = "word", value[1:-1]
        if kind != "space":
            out.append((kind, value, line))
        line += value.count("\n")
        pos = match.end()
    return out


def _sections(path: str, tokens: List[Token]) -> Dict[str, List[Token]]:
    """{section: [(kind, value, line), ...]} between <Generator> and </Generator>."""
    if not tokens or not re.match(r"<Generator[\s>]", tokens[0][1]) or tokens[0][1].endswith("/>"):
        raise InputError(path, "Generator", "expected <Generator> at the top")
    body: Dict[str, List[Token]] = {}
    i = 1
    if i < len(tokens) and tokens[i][0] == "word":
        i += 1                                   # old style: the generator's name as a string
    while i < len(tokens) and tokens[i][:2] != ("tag", "</Generator>"):
        kind, value, line = tokens[i]
        tag = re.match(r"<([A-Za-z]+)", value) if kind == "tag" and not value.startswith("</") else None
        name = tag.group(1) if tag else None
        if name not in SECTIONS:
            raise InputError(path, name or "Generator", "unexpected %r (expected one of %s)" % (value, ", ".join(SECTIONS)),
                             "line %d" % line)
        if name in body:
            raise InputError(path, name, "section given twice", "line %d" % line)
        if value.endswith("/>"):
            body[name], i = [], i + 1
            continue
        end = next((j for j in range(i + 1, len(tokens)) if tokens[j][:2] == ("tag", "</%s>" % name)), None)
        if end is None:
            raise InputError(path, name, "section is not closed", "line %d" % line)
        body[name], i = tokens[i + 1:end], end + 1
    if i >= len(tokens):
        raise InputError(path, "Generator", "missing </Generator>")
    return body


def _names(path: str, section: str, tokens: Sequence[Token]) -> List[str]:
    """State names of a section, expanding <Consecutive> a b </Consecutive> ranges."""
    out: List[str] = []
    i = 0
    while i < len(tokens):
        kind, value, line = tokens[i]
        if (kind, value) == ("tag", "<Consecutive>"):
            first, last = (ascii_int(tokens[i + k][1]) if i + k < len(tokens) else None for k in (1, 2))
            if i + 3 >= len(tokens) or tokens[i + 3][:2] != ("tag", "</Consecutive>") or first is None or last is None:
                raise InputError(path, section, "expected <Consecutive> first last </Consecutive>", "line %d" % line)
            if last - first >= MAX_CONSECUTIVE:
                raise InputError(path, section, "<Consecutive> %d %d: over %d states" % (first, last, MAX_CONSECUTIVE),
                                 "line %d" % line)
            out.extend(str(n) for n in range(first, last + 1))
            i += 4
        elif kind == "word":
            out.append(value)
            i += 1
        elif kind == "attr" and section == "States":
            i += 1
        else:
            raise InputError(path, section, "unexpected %r" % value, "line %d" % line)
    return out


def read_gen(path: str) -> AutomatonFile:
    """One libFAUDES ``.gen`` file -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
    raw = read_input(path)
    text = decode_text(path, raw)
    body = _sections(path, _tokens(path, text))
    build = AutomatonBuilder(path)
    alphabet = body.get("Alphabet", [])
    public = {name.strip('"') for line in PUBLIC.findall(text) for name in line.split()}
    for name in sorted(public - {value for kind, value, _ in alphabet if kind == "word"}):
        raise InputError(path, "swarmvm public", "event %s is not in the Alphabet" % name)
    for i, (kind, value, line) in enumerate(alphabet):
        if kind == "attr":
            continue
        if kind != "word":
            raise InputError(path, "Alphabet", "unexpected %r" % value, "line %d" % line)
        flags = alphabet[i + 1][1] if i + 1 < len(alphabet) and alphabet[i + 1][0] == "attr" else ""
        build.event(value, value, "C" in flags, value in public, key="Alphabet")
    initial = set(_names(path, "InitStates", body.get("InitStates", [])))
    if len(initial) > 1:
        raise InputError(path, "InitStates", "%d initial states; a supervisor has one" % len(initial))
    marked = set(_names(path, "MarkedStates", body.get("MarkedStates", [])))
    states = _names(path, "States", body.get("States", []))
    for section, names in (("InitStates", initial), ("MarkedStates", marked)):
        for name in sorted(names - set(states)):
            raise InputError(path, section, "state %s is not in States" % name)
    for name in states:
        build.state(name, name in initial, name in marked, key="States")
    triples = [t for t in body.get("TransRel", []) if t[0] != "attr"]
    if len(triples) % 3 or any(kind != "word" for kind, _, _ in triples):
        raise InputError(path, "TransRel", "expected triples: source event target")
    for k in range(0, len(triples), 3):
        build.transition(triples[k][1], triples[k + 1][1], triples[k + 2][1], key="TransRel")
    return build.build(len(raw), key="InitStates")
