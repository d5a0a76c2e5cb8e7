"""Read a Nadzoru automaton (``.nza``): a Lua table literal with ``states``, ``events`` and
``transitions``, each a list (Lua indices from 1). A state has ``initial`` and ``marked``;
an event ``name``, ``controllable`` and ``shared`` (Nadzoru's public flag); a transition
``source``, ``target`` and ``event`` as indices into those lists. Layout keys (``x``, ``y``,
``radius_factor``) and ``observable``/``refinement`` are ignored.

The file is parsed as data by :mod:`swarmvm.readers.lua_literal`, never executed."""

from typing import Any, Optional

from ..boundary.errors import InputError, decode_text, read_input
from .automaton import AutomatonBuilder, AutomatonFile
from .lua_literal import LuaSyntaxError, parse_lua_table
from .supervisor_yaml import show_value


def _list(path: str, table: dict[Any, Any], key: str) -> list[dict[Any, Any]]:
    """``table[key]`` as a Python list: a Lua sequence 1..n (an absent key is empty). Its keys
    may be anything Lua allows (strings, booleans, numbers mixed): only integers 1..n pass."""
    value = table.get(key, {})
    if not isinstance(value, dict) or any(type(k) is not int for k in value) \
            or set(value) != set(range(1, len(value) + 1)):
        raise InputError(path, key, "expected a list of tables indexed 1..n")
    for i in value:
        if not isinstance(value[i], dict):
            raise InputError(path, "%s[%d]" % (key, i), "expected a table")
    return [value[i] for i in range(1, len(value) + 1)]


def _flag(path: str, entry: dict[Any, Any], field: str, key: str, default: Optional[bool] = None) -> bool:
    value = entry.get(field, default)
    if not isinstance(value, bool):
        raise InputError(path, "%s.%s" % (key, field), "expected true or false, got %s" % show_value(value))
    return value


def _index(path: str, entry: dict[Any, Any], field: str, key: str, size: int) -> int:
    value = entry.get(field)
    if not isinstance(value, int) or isinstance(value, bool) or not 1 <= value <= size:
        raise InputError(path, "%s.%s" % (key, field), "expected an index in 1..%d, got %s" % (size, show_value(value)))
    return value


def read_nza(path: str) -> AutomatonFile:
    """One ``.nza`` file -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
    raw = read_input(path)
    text = decode_text(path, raw)
    try:
        table = parse_lua_table(text)
    except LuaSyntaxError as exc:
        raise InputError(path, "", "not a Lua table literal: %s" % exc.message, "line %d" % exc.line)
    states, events = _list(path, table, "states"), _list(path, table, "events")
    build = AutomatonBuilder(path)
    for i, entry in enumerate(states, 1):
        key = "states[%d]" % i
        build.state(i, _flag(path, entry, "initial", key, False), _flag(path, entry, "marked", key, False), key)
    for i, entry in enumerate(events, 1):
        key = "events[%d]" % i
        build.event(i, entry.get("name"), _flag(path, entry, "controllable", key),
                    _flag(path, entry, "shared", key, False), key)
    for i, entry in enumerate(_list(path, table, "transitions"), 1):
        key = "transitions[%d]" % i
        build.transition(_index(path, entry, "source", key, len(states)), _index(path, entry, "event", key, len(events)),
                         _index(path, entry, "target", key, len(states)), key=key)
    return build.build(len(raw), key="states")
