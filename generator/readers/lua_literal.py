"""Parse a Lua table literal as data, never as code.

Nadzoru saves automata (``.nza``) as one Lua table constructor. This reads the literal subset
only: tables (``{ [k] = v, name = v, v; ... }``), strings in single or double quotes with
Lua's escapes, decimal and hexadecimal numbers (a leading minus allowed), ``true``,
``false``, ``nil`` and ``--`` comments. Anything else (a call, an operator, a variable) is a
syntax error: nothing in the file is ever executed. Tables come back as dicts keyed by the
Lua keys (positional entries get 1, 2, ...).

What a dict cannot hold as Lua means it is refused, never guessed: a key given twice, a table
as a key (unhashable), a boolean key (Python's ``True`` is the key ``1``), a number literal of
over MAX_NUMBER_LENGTH characters (``int()`` refuses over 4,300 digits; no coordinate or index
needs 64), tables nested deeper than MAX_DEPTH."""

import re
from collections.abc import Iterator
from typing import Any, Dict, Optional, Tuple

MAX_DEPTH = 32
MAX_NUMBER_LENGTH = 64      # characters of one number literal, sign excluded
SHOWN = 40                  # characters of a token or key quoted in a message

TOKEN = re.compile(r"""
    (?P<space>\s+|--[^\n]*)
  | (?P<number>0[xX][0-9a-fA-F]+|(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)
  | (?P<string>"(?:[^"\\\n]|\\.)*"|'(?:[^'\\\n]|\\.)*')
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<punct>[{}\[\]=,;-])
""", re.VERBOSE | re.DOTALL)
ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "a": "\a", "b": "\b", "f": "\f", "v": "\v",
           "\\": "\\", '"': '"', "'": "'", "\n": "\n"}
CONSTANTS = {"true": True, "false": False, "nil": None}


class LuaSyntaxError(ValueError):
    """The text is not a Lua table literal; ``line`` is where reading stopped."""

    def __init__(self, line: int, message: str) -> None:
        super().__init__("line %d: %s" % (line, message))
        self.line, self.message = line, message


def _shown(value: Any) -> str:
    """``value`` quoted for a one-line message, cut at SHOWN characters: a token or a key may
    be a string of a megabyte."""
    text = repr(value)
    return text if len(text) <= SHOWN else text[:SHOWN - 3] + "..."


def _unescape(body: str, line: int) -> str:
    out, i = [], 0
    while i < len(body):
        ch = body[i]
        if ch != "\\":
            out.append(ch)
            i += 1
            continue
        nxt = body[i + 1]
        if "0" <= nxt <= "9":
            found = re.match(r"[0-9]{1,3}", body[i + 1:])
            digits = found.group() if found else nxt
            if int(digits) > 255:
                raise LuaSyntaxError(line, "escape \\%s is out of range" % digits)
            out.append(chr(int(digits)))
            i += 1 + len(digits)
        elif nxt in ESCAPES:
            out.append(ESCAPES[nxt])
            i += 2
        else:
            raise LuaSyntaxError(line, "unknown escape \\%s in a string" % nxt)
    return "".join(out)


def _tokens(text: str) -> Iterator[Tuple[str, str, int]]:
    """(kind, text, line) of each token but white space and comments, then ("end", "", line)."""
    pos, line = 0, 1
    while pos < len(text):
        match = TOKEN.match(text, pos)
        if match is None:
            raise LuaSyntaxError(line, "unexpected character %r" % text[pos])
        kind, value = match.lastgroup or "", match.group()     # (every alternative of TOKEN is a named group)
        if kind != "space":
            yield kind, value, line
        line += value.count("\n")
        pos = match.end()
    yield "end", "", line


class _Parser:
    def __init__(self, text: str) -> None:
        self.tokens = list(_tokens(text))
        self.pos = 0

    def peek(self) -> Tuple[str, str, int]:
        return self.tokens[self.pos]

    def take(self, value: Optional[str] = None) -> Tuple[str, str, int]:
        kind, text, line = self.tokens[self.pos]
        if value is not None and text != value:
            raise LuaSyntaxError(line, "expected %r, found %s" % (value, _shown(text) if text else "end of file"))
        self.pos += 1
        return kind, text, line

    def value(self, depth: int) -> Any:
        kind, text, line = self.take()
        if text == "{":
            return self.table(depth + 1, line)
        if text == "-" and self.peek()[0] == "number":
            return -self.number(self.take()[1], line)
        if kind == "number":
            return self.number(text, line)
        if kind == "string":
            return _unescape(text[1:-1], line)
        if kind == "name" and text in CONSTANTS:
            return CONSTANTS[text]
        raise LuaSyntaxError(line, "expected a value, found %s" % (_shown(text) if text else "end of file"))

    @staticmethod
    def number(text: str, line: int) -> int | float:
        """The number a literal denotes, once its length is bounded (``int()`` of thousands of
        digits is a ValueError; a huge exponent is a float's infinity, as in Lua)."""
        if len(text) > MAX_NUMBER_LENGTH:
            raise LuaSyntaxError(line, "a number of %d characters (at most %d)" % (len(text), MAX_NUMBER_LENGTH))
        if text[:2].lower() == "0x":
            return int(text, 16)
        return float(text) if any(c in text for c in ".eE") else int(text)

    def table(self, depth: int, line: int) -> Dict[Any, Any]:
        if depth > MAX_DEPTH:
            raise LuaSyntaxError(line, "tables nested deeper than %d" % MAX_DEPTH)
        out: Dict[Any, Any] = {}
        position = 1
        while self.peek()[1] != "}":
            kind, text, at = self.peek()
            if text == "[":
                self.take()
                key = self.value(depth)
                self.take("]")
                self.take("=")
            elif kind == "name" and text not in CONSTANTS and self.tokens[self.pos + 1][1] == "=":
                key = text
                self.pos += 2
            else:
                key, position = position, position + 1
            if key is None or isinstance(key, (dict, bool)):
                what = "nil" if key is None else "a table" if isinstance(key, dict) else "a boolean"
                raise LuaSyntaxError(at, "a key must be a string or a number, not %s" % what)
            if key in out:
                raise LuaSyntaxError(at, "key %s given twice" % _shown(key))
            out[key] = self.value(depth)
            if self.peek()[1] in (",", ";"):
                self.take()
            elif self.peek()[1] != "}":
                found = self.peek()[1]
                raise LuaSyntaxError(self.peek()[2], "expected ',' or '}', found %s" % (_shown(found) if found else "end of file"))
        self.take("}")
        return out


def parse_lua_table(text: str) -> Dict[Any, Any]:
    """The table a file's single table constructor denotes (an optional ``return`` first)."""
    parser = _Parser(text)
    if parser.peek()[1] == "return":
        parser.take()
    kind, first, line = parser.take()
    if first != "{":
        raise LuaSyntaxError(line, "expected a table constructor '{', found %s" % (_shown(first) if first else "end of file"))
    table = parser.table(1, line)
    if parser.peek()[0] != "end":
        raise LuaSyntaxError(parser.peek()[2], "unexpected %s after the table" % _shown(parser.peek()[1]))
    return table
