"""The bounds every structured input is held to before its parser sees it: how deep its lists and
tables nest, and how many digits a number has.

Python's parsers have no such bounds of their own: ``tomllib`` and ``json`` recurse once per
level (a budget file nested 50,000 deep ended in a RecursionError traceback) and ``int()``
refuses over 4,300 digits with a ValueError. The check here is a scan of the text that skips
strings and comments, counting brackets and digit runs: it accepts every file swarmvm writes or
a user would (supervisor files nest three deep, reports four) and refuses the rest in one line
naming the file and the line."""

import json
import re
from typing import Any

from .errors import InputError, decode_text, read_input

MAX_NESTING = 64    # a footprint report nests four levels, a budget file three
MAX_DIGITS = 64     # far past any count, size or figure; int() itself stops at 4,300
_NUMBER = re.compile(r"[0-9][0-9_]*")
_OPEN, _CLOSE = "[{", "]}"


def check_structure(path: str, text: str, comment: str = "") -> None:
    """InputError when ``text`` (JSON, or TOML with ``comment="#"``) nests lists and tables more
    than MAX_NESTING deep or holds a number of more than MAX_DIGITS digits. Strings ("...",
    '...', and TOML's triple-quoted ones) and comments are skipped."""
    depth, line, i, n = 0, 1, 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        elif comment and c == comment:
            end = text.find("\n", i)
            i = n if end < 0 else end
            continue
        elif c in "\"'":
            quote = text[i:i + 3] if text[i:i + 3] in ('"""', "'''") else c
            j = i + len(quote)
            while j < n and not text.startswith(quote, j):
                j += 2 if text[j] == "\\" and c == '"' else 1
            line += text.count("\n", i, j)
            i = j + len(quote)
            continue
        elif c in _OPEN:
            depth += 1
            if depth > MAX_NESTING:
                raise InputError(path, "", "lists or tables nested more than %d deep" % MAX_NESTING, "line %d" % line)
        elif c in _CLOSE:
            depth = max(0, depth - 1)
        elif c.isdigit():
            run = _NUMBER.match(text, i)
            end = run.end() if run else i + 1
            if end - i > MAX_DIGITS:
                raise InputError(path, "", "a number of %d digits: at most %d" % (end - i, MAX_DIGITS), "line %d" % line)
            i = end
            continue
        i += 1


def read_json_document(path: str, format_name: str, version: int, what: str, again: str,
                       limit: int | None = None) -> dict[str, Any]:
    """The JSON object of a file swarmvm wrote (a footprint report, a sidecar): read through the
    input layer, bounded as above, its ``format`` ``format_name`` and its ``version`` this one;
    otherwise one InputError naming the file and the key, ``what`` naming the kind of file and
    ``again`` saying how to write it anew. Its other keys are the caller's to check."""
    text = decode_text(path, read_input(path) if limit is None else read_input(path, limit=limit))
    check_structure(path, text)
    try:
        data = json.loads(text)
    except ValueError as exc:                           # JSONDecodeError
        raise InputError(path, "", "not a JSON file (%s): %s" % (exc, again))
    if not isinstance(data, dict) or data.get("format") != format_name:
        raise InputError(path, "format", "not a swarmvm %s (%s)" % (what, again))
    if data.get("version") != version:
        raise InputError(path, "version", "a %s of version %s; this swarmvm reads version %d (%s)"
                         % (what, json.dumps(data.get("version")), version, again))
    return data
