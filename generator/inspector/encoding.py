"""The compact encoding of a page's runs (docs/inspect.md, "Size"): what lets one page hold a
swarm's run (200 robots x 20,000 steps, 4 M robot-steps) and open in a second.

A page's data (swarmvm.inspector.page) holds one table for all its runs, ``table``: the distinct
steps of the traces (swarmvm.inspector.trace.Steps), each ``[vector, fired, added]``, the numbers
of its vector of states after the step (in ``vectors``) and of the events it fired in firing
order (in ``fired``), and the violations it added. A run is then one integer a step, its row of
the table, its *code*: ``run.codes`` is the base64 of ``run.kept`` little-endian unsigned
integers of ``codeBytes`` bytes each (2 while the table has at most 65,536 rows, else 4), the
steps kept from ``first``. Index 0 of a run is the state before its first step kept: vector
``run.start``, violation counter ``run.startViolations``; index i (1 .. kept) is step ``first +
i - 1``, whose vector and fired events are its code's, and whose counter is ``startViolations``
plus the ``added`` of the codes of indices 1 .. i.

The page's script (templates/inspect/inspect.js) turns a run's base64 into a typed array of
codes when it first needs the run, and looks a step's states and events up in the table when it
shows that step: opening the page parses no per-step JSON and builds no per-step object.
:func:`decode` is the same reading in Python, for whoever checks a page's data against traces
(the tests, the conformance checks of the runtimes' traces)."""

from __future__ import annotations

import base64
import sys
from array import array
from typing import Any

SHORT = 1 << 16          # table rows up to which a code takes 2 bytes


def code_bytes(rows: int) -> int:
    """The bytes of one code for a table of ``rows`` rows."""
    return 2 if rows <= SHORT else 4


def pack(codes: array[int], width: int) -> str:
    """``codes`` as the base64 of little-endian unsigned integers of ``width`` bytes (the same
    text on any machine)."""
    packed = array("H" if width == 2 else "I", codes)
    if sys.byteorder == "big":
        packed.byteswap()
    return base64.b64encode(packed.tobytes()).decode("ascii")


def unpack(text: str, width: int) -> list[int]:
    """The codes :func:`pack` wrote."""
    packed = array("H" if width == 2 else "I", base64.b64decode(text, validate=True))
    if sys.byteorder == "big":
        packed.byteswap()
    return packed.tolist()


Step = tuple[list[int], list[int], int]    # the states after, the events fired, the violation counter after


def decode(data: dict[str, Any], run: dict[str, Any]) -> list[Step]:
    """One run of a page's ``data``, index by index (0: the states before its first step kept,
    with no event fired)."""
    table, vectors, fired = data["table"], data["vectors"], data["fired"]
    violations = run["startViolations"]
    steps: list[Step] = [(vectors[run["start"]], [], violations)]
    for code in unpack(run["codes"], data["codeBytes"]):
        vector, events, added = table[code]
        violations += added
        steps.append((vectors[vector], fired[events], violations))
    return steps
