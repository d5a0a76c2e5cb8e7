"""Read a supervisor from the C tables Nadzoru generates for its generic microcontroller VM.

The published Kilobot and CapBot programs carry their supervisor only as C: ``#define EV_x n``
for each event, then ``ev_controllable``, ``sup_events``, ``sup_init_state``,
``sup_current_state``, ``sup_data_pos`` and ``sup_data`` as initialised arrays (the CapBot's
``lib/sct/src/*.c`` takes the defines from its header through ``#include "x.h"``; the Kilobot
program inlines both). These are the arrays of Nadzoru 2's ``supervisor.yaml`` under the same
names, so this reader turns them into that document, every value a string as the YAML reader
sees it, and the YAML reader's own checks validate it: one validation for both forms.

Only what the tables need is read: comments are dropped, ``#define NAME <integer>`` is recorded,
``#include "..."`` is followed (beside the file, then in ``../inc`` and ``../include``, as the
CapBot's layout has it), every other directive is skipped, and every declaration other than the
tables is ignored, so a whole program can be given. Nothing is compiled or evaluated: an array
entry is an integer literal, a defined name, or an ``EV_`` name."""

import hashlib
import os
import re
from typing import Union

from ..boundary.errors import InputError, decode_text, read_input
from ..compiler.model import Supervisors
from .supervisor_yaml import OPTIONAL, REQUIRED, supervisor_from_document

# The tables a supervisor.yaml holds that C declares as arrays (the counts come from defines).
TABLES = tuple(key for key in REQUIRED + OPTIONAL if key not in ("num_events", "num_supervisors", "events"))
INCLUDE_DIRS = (".", os.path.join("..", "inc"), os.path.join("..", "include"))
MAX_INCLUDE_DEPTH = 8
MAX_NESTING = 4        # sup_events is two deep; nothing Nadzoru writes is deeper
MAX_LITERAL = 20       # characters of an integer literal: 2**64 in hex with suffixes fits; int() is not asked more
TOKEN = re.compile(r"(?P<number>[0-9][0-9A-Za-z]*)|(?P<name>[A-Za-z_]\w*)|(?P<punct>[{},=;\[\]])|(?P<other>\S)")
INTEGER = re.compile(r"(?:0[xX](?P<hex>[0-9A-Fa-f]+)|(?P<dec>[0-9]+))[uUlL]{0,3}\Z")
DEFINE = re.compile(r"#\s*define\s+(?P<name>[A-Za-z_]\w*)[ \t]+(?P<value>\S+)\s*\Z")
INCLUDE = re.compile(r'#\s*include\s+"(?P<file>[^"]+)"')

Value = Union[str, list["Value"]]


def _without_comments(text: str) -> str:
    """``text`` with every comment replaced by spaces (newlines kept, so line numbers hold);
    string and character literals are skipped whole, so ``"/*"`` in one starts no comment."""
    out, i, n = [], 0, len(text)
    while i < n:
        two = text[i:i + 2]
        if two == "/*":
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
        elif two == "//":
            end = text.find("\n", i)
            end = n if end < 0 else end
            out.append(" " * (end - i))
            i = end
        elif text[i] in "\"'":
            quote, j = text[i], i + 1
            while j < n and text[j] not in (quote, "\n"):
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def _integer(text: str) -> Union[int, None]:
    """The value of a C integer literal (decimal or hex, with u/l suffixes), else None."""
    match = INTEGER.match(text) if len(text) <= MAX_LITERAL else None
    if match is None:
        return None
    return int(match.group("hex"), 16) if match.group("hex") else int(match.group("dec"))


class _Source:
    """The files read (the one given and what it includes), their defines, and the code with
    directives blanked out, each line tagged with its file and line for messages."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.defines: dict[str, int] = {}
        self.missing: list[str] = []        # quoted includes that were not found
        self.code: list[tuple[str, int, str]] = []
        self.raw = b""
        self._read(path, 0, set())

    def _read(self, path: str, depth: int, seen: set[str]) -> None:
        real = os.path.realpath(path)
        if real in seen:
            return
        seen.add(real)
        raw = read_input(path)
        if depth == 0:
            self.raw = raw
        text = _without_comments(decode_text(path, raw)).replace("\\\n", " \n")
        for number, line in enumerate(text.split("\n"), 1):
            stripped = line.strip()
            if not stripped.startswith("#"):
                self.code.append((path, number, line))
                continue
            define, include = DEFINE.match(stripped), INCLUDE.match(stripped)
            if define and define.group("value")[:1].isdigit() and len(define.group("value")) > MAX_LITERAL:
                raise InputError(path, define.group("name"), "value of over %d characters" % MAX_LITERAL,
                                 "line %d" % number)
            if define and _integer(define.group("value")) is not None:
                self.defines[define.group("name")] = _integer(define.group("value")) or 0
            elif include and depth < MAX_INCLUDE_DEPTH:
                found = self._find(path, include.group("file"))
                if found is None:
                    self.missing.append(include.group("file"))
                else:
                    self._read(found, depth + 1, seen)

    @staticmethod
    def _find(including: str, name: str) -> Union[str, None]:
        folder = os.path.dirname(including)
        for where in INCLUDE_DIRS:
            candidate = os.path.normpath(os.path.join(folder, where, name))
            if os.path.isfile(candidate):
                return candidate
        return None


class _Tables:
    """The initialised arrays named in TABLES, parsed from the code's tokens."""

    def __init__(self, source: _Source) -> None:
        self.source = source
        self.tokens: list[tuple[str, str, str, int]] = []      # (kind, text, file, line)
        for path, number, line in source.code:
            for match in TOKEN.finditer(line):
                kind = match.lastgroup or "other"
                self.tokens.append((kind, match.group(kind), path, number))
        self.arrays: dict[str, Value] = {}
        self._find_tables()

    def _fail(self, at: int, key: str, message: str) -> InputError:
        _, _, path, line = self.tokens[min(at, len(self.tokens) - 1)]
        return InputError(path, key, message, "line %d" % line)

    def _find_tables(self) -> None:
        i = 0
        while i < len(self.tokens):
            kind, text, _, _ = self.tokens[i]
            if kind == "name" and text in TABLES and self._declares(i):
                if text in self.arrays:
                    raise self._fail(i, text, "defined twice")
                i = self._table(i, text)
            else:
                i += 1

    def _declares(self, i: int) -> bool:
        """Token i names an array being defined: ``name [..]... [ATTRIBUTE...] = {``."""
        j, dims = i + 1, 0
        while j < len(self.tokens) and self.tokens[j][1] == "[":
            while j < len(self.tokens) and self.tokens[j][1] != "]":
                j += 1
            j, dims = j + 1, dims + 1
        while j < len(self.tokens) and self.tokens[j][0] == "name":     # PROGMEM and the like
            j += 1
        return dims > 0 and j + 1 < len(self.tokens) and self.tokens[j][1] == "=" and self.tokens[j + 1][1] == "{"

    def _table(self, i: int, key: str) -> int:
        """Parse the table named at token i; the index after its closing brace."""
        j = i + 1
        while self.tokens[j][1] != "=":
            j += 1
        value, j = self._initialiser(j + 1, key, 1)
        self.arrays[key] = value
        return j

    def _initialiser(self, j: int, key: str, depth: int) -> tuple[Value, int]:
        if depth > MAX_NESTING:
            raise self._fail(j, key, "braces nested more than %d deep" % MAX_NESTING)
        items: list[Value] = []
        j += 1                                      # past "{"
        while j < len(self.tokens):
            kind, text, _, _ = self.tokens[j]
            if text == "}":
                return items, j + 1
            if text == "{":
                item, j = self._initialiser(j, key, depth + 1)
                items.append(item)
            elif kind in ("number", "name"):
                items.append(self._entry(j, "%s[%d]" % (key, len(items))))
                j += 1
            else:
                raise self._fail(j, key, "expected an integer, a defined name or '}', got %r" % text)
            if j < len(self.tokens) and self.tokens[j][1] == ",":
                j += 1
            elif j < len(self.tokens) and self.tokens[j][1] != "}":
                raise self._fail(j, key, "expected ',' or '}', got %r" % self.tokens[j][1])
        raise self._fail(j, key, "the initialiser has no closing '}'")

    def _entry(self, j: int, key: str) -> str:
        """An entry as the YAML reader would see it: digits, or an ``EV_`` name (kept, as
        sup_data holds them), or a defined name's integer."""
        kind, text, _, _ = self.tokens[j]
        if kind == "number":
            number = _integer(text)
            if number is None:
                raise self._fail(j, key, "%r is not an integer literal of at most %d characters"
                                 % (text[:40], MAX_LITERAL))
            return str(number)
        if text.startswith("EV_") and text in self.source.defines:
            return text
        if text in self.source.defines:
            return str(self.source.defines[text])
        hint = (" (not found: %s; give the file that defines it, or put it beside this one)"
                % ", ".join('"%s"' % m for m in self.source.missing)) if self.source.missing else ""
        raise self._fail(j, key, "%s is not defined%s" % (text[:60], hint))


def _events(source: _Source, count: int) -> list[str]:
    """The ``EV_`` defines in value order, which must number the events 0..count-1."""
    by_value: dict[int, str] = {}
    for name, value in source.defines.items():
        if name.startswith("EV_"):
            if value in by_value:
                raise InputError(source.path, name, "has the value %d of %s too" % (value, by_value[value]))
            by_value[value] = name
    if sorted(by_value) != list(range(len(by_value))) or len(by_value) != count:
        raise InputError(source.path, "events", "the EV_ defines number %d events as %s; the tables have %d "
                         "(each event defined once, numbered from 0)" % (len(by_value), sorted(by_value)[:8], count))
    return [by_value[value] for value in range(count)]


def read_nadzoru_c(path: str, published: bool = False) -> Supervisors:
    """The supervisor in the C source or header ``path`` (and the files it includes), or
    InputError naming the file, the table and the line."""
    source = _Source(path)
    tables = _Tables(source)
    needed = [key for key in REQUIRED if key in TABLES]
    absent = [key for key in needed if key not in tables.arrays]
    if len(absent) == len(needed):
        raise InputError(path, "", "not a Nadzoru C supervisor: it defines none of its tables (%s)" % ", ".join(needed))
    if absent:
        raise InputError(path, absent[0], "table not defined here (a Nadzoru C supervisor defines %s)"
                         % ", ".join(needed))
    # The counts: the defines the published programs have, else the tables' lengths.
    controllable, supervisors = tables.arrays["ev_controllable"], tables.arrays["sup_init_state"]
    events = source.defines.get("NUM_EVENTS", len(controllable) if isinstance(controllable, list) else 0)
    doc: dict[str, object] = dict(tables.arrays)
    doc["num_events"] = str(events)
    doc["num_supervisors"] = str(source.defines.get("NUM_SUPERVISORS",
                                                    len(supervisors) if isinstance(supervisors, list) else 0))
    doc["events"] = _events(source, events)
    spec = supervisor_from_document(path, doc, published)
    spec.size_bytes = len(source.raw)
    spec.digest = hashlib.sha256(source.raw).digest()
    return spec
