"""Which C file of the tree calls a function another one defines, read from the source text (no
compiler): the graph in which test_layers looks for cycles among C files, as among Python modules.

A C file "depends on" another when it calls (or names) a function the other defines with external
linkage; a cycle is two files, or more, each calling the next one's functions, like the
conformance harness calling its platform's output while the platform called the harness's run.
Every preprocessor branch counts (a call under any #if is a dependency of some build); a name
defined in several files (main, one platform function per platform) links each caller to all of
them."""

from __future__ import annotations

import re
from pathlib import Path

# Comments, then string and character literals: neither calls anything.
_COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)
_LITERAL = re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'')
# A function definition at the start of a line: a return type, the name, a parameter list and
# the opening brace (on the same line or the next). Prototypes end in ';' and do not match.
_DEFINITION = re.compile(r"^(?P<head>[A-Za-z_][\w \t*]*?)\b(?P<name>[A-Za-z_]\w*)\s*\([^;{}()]*\)\s*\{", re.M)
_NAME_USE = re.compile(r"\b([A-Za-z_]\w*)\s*\(")


def _code(path: Path) -> str:
    return _LITERAL.sub('""', _COMMENT.sub(" ", path.read_text()))


def definitions(code: str) -> dict[str, bool]:
    """The functions ``code`` defines -> whether other files can call them (not ``static``)."""
    return {m["name"]: "static" not in m["head"].split() for m in _DEFINITION.finditer(code)
            if m["name"] not in ("if", "for", "while", "switch")}


def call_graph(files: list[Path], root: Path) -> dict[str, set[str]]:
    """File (relative to ``root``) -> the files whose external functions it calls."""
    codes = {path.relative_to(root).as_posix(): _code(path) for path in files}
    defined_in: dict[str, set[str]] = {}
    for name, code in codes.items():
        for function, external in definitions(code).items():
            if external:
                defined_in.setdefault(function, set()).add(name)
    graph = {}
    for name, code in codes.items():
        used = set(_NAME_USE.findall(code)) - set(definitions(code))     # its own, static or not, are local
        graph[name] = {other for function in used for other in defined_in.get(function, ()) if other != name}
    return graph
