"""The one place where user text enters swarmvm's output: a function per output context.

File names, model and event names, keys and paths come from other people's files. Wherever
swarmvm writes them (generated C, C++, Python, Make and CMake text, YAML, libFAUDES ``.gen``,
Graphviz, Markdown, HTML, the terminal) they pass through the function for that context here,
and nowhere else. Each function returns text that, placed in its context, is read back as data:
it cannot end a comment or string, start a command, continue a line or move the cursor.

Templates reach these only as Jinja filters (:data:`FILTERS`); tests/boundary/test_template_filters.py
fails a template that writes a value through no filter. Text a context cannot represent raises
:class:`UnsafeText`, a ValueError, which the callers turn into an InputError naming the input.

Unprintable and (where the context needs ASCII) non-ASCII characters are written as Python's
escapes (``\\n``, ``\\x1b``, ``\\u202e``), so what a person reads names the character."""

import html as _html
import json
import re
from typing import Any

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_IDENTIFIER_PART = re.compile(r"[A-Za-z0-9_]*\Z")
_MAKE_WORD = re.compile(r"[A-Za-z0-9_+=,./:@-]+\Z")
# Characters a comment keeps as they are in every language swarmvm writes comments in (C, C++,
# Python, Make, CMake, YAML, .gen, XML): none can end or nest a comment (``*/``, ``/*``, and
# ``--`` is split), continue a line (a trailing backslash), form a trigraph (``??/``) or end a
# docstring (``"""``).
_COMMENT_SAFE = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                          " _-.,:;+=()[]{}<>@!%&^~|'#/$")
# What can change a Markdown table's structure or make a link, HTML or code of text: a cell
# cannot split, nothing becomes a link or a tag. Emphasis (``_``) is left: names hold it.
_MARKDOWN_SPECIAL = frozenset("\\`*[]<>|")


class UnsafeText(ValueError):
    """User text that a context cannot represent (an identifier that is not one, say)."""


def _escape(char: str) -> str:
    """``char`` as Python writes it escaped: ``\\n``, ``\\x1b``, ``\\u202e``, ``\\U0001f600``."""
    if char in "\n\t\r":
        return {"\n": "\\n", "\t": "\\t", "\r": "\\r"}[char]
    code = ord(char)
    if code < 0x100:
        return "\\x%02x" % code
    return "\\u%04x" % code if code < 0x10000 else "\\U%08x" % code


def terminal(text: str) -> str:
    """``text`` for a terminal line: each unprintable character (a line break, an escape
    sequence's ESC, a bidirectional override, NUL) written as its escape, so a message stays one
    line and sends the terminal nothing but text."""
    return text if text.isprintable() else "".join(c if c.isprintable() else _escape(c) for c in text)


# User text in a message (a file name, a key, a token, a value) is cut to this many characters,
# the cut said: a message stays a line a person reads, whatever a file holds (docs/limits.md).
MESSAGE_PART_LIMIT = 1000
MESSAGE_LINE_LIMIT = 5 * MESSAGE_PART_LIMIT     # a whole message line: its four parts and more


def bounded(text: str, limit: int = MESSAGE_PART_LIMIT) -> str:
    """``text``, cut to ``limit`` characters with the cut said when it is longer."""
    if len(text) <= limit:
        return text
    return "%s... (%d more characters cut)" % (text[:limit], len(text) - limit)


def comment(text: str) -> str:
    """``text`` inside a comment of C (``/* */`` and ``//``), C++, Python (``#`` and
    docstrings), Make, CMake, YAML or ``.gen``: ASCII that cannot end the comment, with every
    other character (a newline, ``*``, ``?``, a backslash, a quote, non-ASCII) escaped, and
    ``--`` (which ends an XML comment) split as ``-\\x2d``."""
    return "".join(c if c in _COMMENT_SAFE else _escape(c) for c in text).replace("--", "-\\x2d")


def c_string(text: str) -> str:
    """A C or C++ string literal (quotes included) holding ``text``'s UTF-8 bytes: printable
    ASCII as itself, ``"``, ``\\`` and ``?`` (trigraphs) escaped, other bytes in octal, which
    unlike ``\\x`` cannot swallow the digits after it."""
    out = []
    for byte in text.encode("utf-8"):
        char = chr(byte)
        if char in '"\\?':
            out.append("\\" + char)
        elif 0x20 <= byte < 0x7F:
            out.append(char)
        else:
            out.append("\\%03o" % byte)
    return '"%s"' % "".join(out)


def _double_quoted(text: str) -> str:
    """``text`` between double quotes with ``"`` and ``\\`` escaped and every character outside
    printable ASCII as its escape: a string literal of Python and a double-quoted scalar of YAML
    alike (both read ``\\xHH``, ``\\uHHHH`` and ``\\UHHHHHHHH``)."""
    return '"%s"' % "".join("\\" + c if c in '"\\' else c if " " <= c <= "~" else _escape(c) for c in str(text))


def py_string(text: str) -> str:
    """A double-quoted Python string literal equal to ``text``, in ASCII."""
    return _double_quoted(text)


def cmake_string(text: str) -> str:
    """A CMake quoted argument equal to ``text``: ``\\``, ``"`` and ``$`` (variable references)
    escaped, line breaks and tabs as ``\\n``/``\\t``/``\\r``; other control characters have no
    CMake spelling and raise UnsafeText. (A ``;`` stays: it is a list separator only where the
    value is later expanded unquoted.)"""
    out = []
    for char in text:
        if char in '\\"$':
            out.append("\\" + char)
        elif char in "\n\t\r":
            out.append(_escape(char))
        elif not char.isprintable():
            raise UnsafeText("%s: a control character CMake cannot quote" % terminal(text))
        else:
            out.append(char)
    return '"%s"' % "".join(out)


def yaml_string(text: str) -> str:
    """A YAML double-quoted scalar equal to ``text``, in ASCII."""
    return _double_quoted(text)


def gen_string(text: str) -> str:
    """A libFAUDES token-format string (quotes included). libFAUDES strings have no escapes:
    ``text`` must be printable ASCII without ``"`` or white space, else UnsafeText."""
    if not text or not text.isascii() or not text.isprintable() or '"' in text or " " in text:
        raise UnsafeText("%s: not a libFAUDES name (printable ASCII, no quote or space)" % terminal(text))
    return '"%s"' % text


def dot_text(text: str) -> str:
    """``text`` inside a Graphviz double-quoted ID, drawn as it is: unprintable characters
    shown as their escapes, ``\\`` and ``"`` escaped (Graphviz reads ``\\n``, ``\\l``, ``\\N``
    in labels as commands)."""
    return terminal(text).replace("\\", "\\\\").replace('"', '\\"')


def dot_string(text: str) -> str:
    """A Graphviz double-quoted ID (quotes included) drawn as ``text`` (:func:`dot_text`)."""
    return '"%s"' % dot_text(text)


def markdown(text: str) -> str:
    """``text`` as literal Markdown inline text (a table cell, say): unprintable characters
    shown as their escapes, then the characters that could split a cell or make a link, a tag
    or code (``|``, brackets, ``<``, backquotes, ``*``, ``\\``) backslash-escaped."""
    return "".join("\\" + c if c in _MARKDOWN_SPECIAL else c for c in terminal(text))


def html(text: str) -> str:
    """``text`` as HTML text or a quoted attribute value: unprintable characters shown as
    their escapes, then ``& < > " '`` as entities."""
    return _html.escape(terminal(text), quote=True)


_SCRIPT_JSON_ESCAPES = {"<": "\\u003c", ">": "\\u003e", "&": "\\u0026", "\u2028": "\\u2028", "\u2029": "\\u2029"}


def script_json(value: Any) -> str:
    """``value`` as JSON text that can sit inside an HTML ``<script>`` element: ``<``, ``>`` and
    ``&`` (and the two line separators JavaScript once refused) written as ``\\u`` escapes, so
    no name, ``</script>`` included, can end the element or open a comment. Keys sorted: the
    same value, the same bytes."""
    text = json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    for char, escape in _SCRIPT_JSON_ESCAPES.items():      # no escape holds a character escaped
        text = text.replace(char, escape)                   # (str.replace: an inspector page is MBs)
    return text


def identifier(text: str) -> str:
    """``text`` when it is an ASCII identifier (C, C++, Python, Make and CMake take it as it
    is), else UnsafeText: names reach generated code only as identifiers validated here."""
    if not isinstance(text, str) or not _IDENTIFIER.match(text):
        raise UnsafeText("%s is not an identifier" % terminal(repr(text)))
    return text


def identifier_part(text: str) -> str:
    """``text`` when it can continue an identifier (ASCII letters, digits, ``_``, or nothing: the
    event ``EV_`` has the empty name, and ``on_`` its callback), else UnsafeText."""
    if not isinstance(text, str) or not _IDENTIFIER_PART.match(text):
        raise UnsafeText("%s cannot be part of an identifier" % terminal(repr(text)))
    return text


def make_words(text: str) -> str:
    """``text``'s words, one space apart, when each is a word Make and the shell take as it is
    (letters, digits and ``_+=,./:@-``: compiler flags, file names of the package), else
    UnsafeText: a Makefile's variable gets no quoting, so nothing that would need it is written."""
    words = text.split() if isinstance(text, str) else None
    if not words or not all(_MAKE_WORD.match(word) for word in words):
        raise UnsafeText("%s: not words a Makefile can hold unquoted" % terminal(repr(text)))
    return " ".join(words)


def number(value: object, width: int = 0) -> str:
    """An integer as decimal text, left-justified to ``width``; UnsafeText for anything else (a
    str that looks like a number included), so a template cannot pass text off as a number."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise UnsafeText("%s is not an integer" % terminal(repr(value)))
    return str(value).ljust(width)


# The Jinja filters the templates use to write a value (swarmvm.compiler.render.ENV); every ``{{ }}``
# of a template ends in one of these, or in one of render's filters of bytes and numbers.
FILTERS = {
    "comment": comment,
    "c_string": c_string,
    "py_string": py_string,
    "cmake_string": cmake_string,
    "yaml_string": yaml_string,
    "markdown": markdown,
    "ident": identifier,
    "ident_part": identifier_part,
    "make_words": make_words,
    "num": number,
}
