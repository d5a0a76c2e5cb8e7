"""The synthesis script form (docs/models.md), read as data: one statement a line.

    Gloc1 = Sync(G1, G3)          # parallel composition of two or more automata
    Kloc1 = Sync(Gloc1, E1)
    Sloc1 = SupC(Gloc1, Kloc1)    # supremal controllable (non-blocking) sublanguage
    Sloc1 = Minimize(Sloc1)       # state minimisation (also Min)
    export(Sloc1, Sloc2)          # the supervisors that form the output set, in order

Operation names are case-insensitive, so Nadzoru 2's ``script.txt`` and Nadzoru's Lua spelling
(``sync``, ``supc``, ``minimize``, ``export``) both read; ``#`` and ``--`` start comments and
Nadzoru's ``print(...)`` lines are skipped. Nothing is evaluated: a line that is not one of
these forms is an error naming its line."""

import re
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

from ..boundary.errors import InputError, decode_text, read_input

OPERATIONS = {"sync": "sync", "supc": "supc", "minimize": "min", "minimise": "min", "min": "min"}
ARITY = {"sync": (2, None), "supc": (2, 2), "min": (1, 1)}
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
ASSIGN = re.compile(r"(%s)\s*=\s*(%s)\s*\((.*)\)\s*;?\Z" % (IDENT, IDENT))
CALL = re.compile(r"(%s)\s*\((.*)\)\s*;?\Z" % IDENT)


@dataclass(frozen=True)
class Step:
    """``target = op(args)``; ``line`` is the script line, for messages."""
    target: str
    op: str
    args: Tuple[str, ...]
    line: int


@dataclass(frozen=True)
class SynthScript:
    source: str
    steps: Tuple[Step, ...]
    exports: Tuple[str, ...]      # empty: every name a SupC assigned, in order of first assignment


def _strip_comment(line: str) -> str:
    """``line`` up to a ``#`` or ``--`` that is not inside a quoted string."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch == "#" or line.startswith("--", i):
            return line[:i]
    return line


def _arguments(source: str, text: str, number: int, what: str) -> Tuple[str, ...]:
    args = tuple(a.strip() for a in text.split(",")) if text.strip() else ()
    for arg in args:
        if not re.fullmatch(IDENT, arg):
            raise InputError(source, what, "%r is not a name" % arg, "line %d" % number)
    return args


def parse_synth_script(source: str, text: str) -> SynthScript:
    """Statements of a synthesis script (``source`` names it in errors)."""
    steps: list[Step] = []
    exports: list[str] = []
    for number, raw in enumerate(text.splitlines(), 1):
        line = _strip_comment(raw).strip()
        if not line:
            continue
        match = ASSIGN.match(line)
        if match:
            target, name, args = match.groups()
            op = OPERATIONS.get(name.lower())
            if op is None:
                raise InputError(source, name, "unknown operation (expected Sync, SupC or Minimize)", "line %d" % number)
            args = _arguments(source, args, number, name)
            low, high = ARITY[op]
            if len(args) < low or (high is not None and len(args) > high):
                wanted = "%d" % low if low == high else "at least %d" % low
                raise InputError(source, name, "takes %s argument(s), got %d" % (wanted, len(args)), "line %d" % number)
            steps.append(Step(target, op, args, number))
            continue
        match = CALL.match(line)
        if match and match.group(1).lower() == "export":
            exports.extend(_arguments(source, match.group(2), number, "export"))
            continue
        if match and match.group(1).lower() == "print":
            continue
        raise InputError(source, "script", "not a statement: %r (expected NAME = Op(ARGS) or export(NAMES))" % raw.strip(),
                         "line %d" % number)
    if not steps:
        raise InputError(source, "script", "no statements")
    return SynthScript(source, tuple(steps), tuple(exports))


def read_synth_script(path: Optional[str], statements: Sequence[str]) -> SynthScript:
    """The script of ``swarmvm synth``: a file, or statements given as options (not both)."""
    if (path is None) == (not statements):
        raise InputError(path or "--statement", "", "give a script file (--script) or statements (-e), one of the two")
    if path is None:
        return parse_synth_script("--statement", "\n".join(statements))
    return parse_synth_script(path, decode_text(path, read_input(path)))
