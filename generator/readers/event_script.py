"""Event scripts: the target-independent input of the conformance contract (docs/conformance.md).

A script says, for each step, which uncontrollable events' checks return true. As text: one
line per step listing ``EV_`` names separated by spaces, or ``-`` for none; ``#`` starts a
comment line."""

import io
import random
import sys
from itertools import chain
from typing import BinaryIO, Iterable, Iterator, Sequence

from ..boundary.errors import MAX_BYTES, InputError, decode_text, open_input
from ..compiler.tables import Tables

MAX_STEPS = 10 ** 7             # steps in a script: what ``swarmvm script --steps`` writes at most
MAX_LINE_BYTES = 1 << 17        # a line naming each of 255 events of 255 characters fits
STDIN = "-"                     # the script name that means standard input (``trace --script -``)
STDIN_NAME = "<stdin>"          # how messages name it

Row = set[int]                  # one step of a script: the indices of the events that occur


def parse_lines(path: str, lines: Iterable[str], names: Sequence[str], controllable: int) -> Iterator[Row]:
    """Lines of a script (str) -> its rows (sets of event indices), one at a time; InputError
    at the first bad line. ``names`` are the image's bare event names."""
    index = {"EV_" + n: i for i, n in enumerate(names)}
    for number, line in enumerate(lines, 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        row: Row = set()
        if line != "-":
            for token in line.split():
                if token not in index:
                    raise InputError(path, "line %d" % number, "unknown event", "event %s" % token)
                if controllable >> index[token] & 1:
                    raise InputError(path, "line %d" % number, "controllable events are chosen by the VM, "
                                     "not scripted", "event %s" % token)
                row.add(index[token])
        yield row


def parse_script(path: str, text: str, names: Sequence[str], controllable: int) -> list[Row]:
    """Text -> list of sets of event indices. ``names`` are the image's bare event names."""
    return list(parse_lines(path, text.splitlines(), names, controllable))


def handle_lines(name: str, handle: BinaryIO, first: int = 1) -> Iterator[str]:
    """The lines of an open binary handle, decoded one at a time and numbered from ``first``
    (InputError naming ``name`` for a line that is not UTF-8 or longer than MAX_LINE_BYTES)."""
    for number, raw in enumerate(iter(lambda: handle.readline(MAX_LINE_BYTES + 1), b""), first):
        if len(raw) > MAX_LINE_BYTES:
            raise InputError(name, "line %d" % number, "line over the %d-byte limit" % MAX_LINE_BYTES)
        yield decode_text(name, raw, "line %d" % number, " of the line")


def file_lines(path: str) -> Iterator[str]:
    """The lines of a regular file, decoded one at a time (:func:`handle_lines`)."""
    try:
        with open_input(path) as handle:
            yield from handle_lines(path, handle)
    except OSError as exc:
        raise InputError(path, "", "cannot read file (%s)" % exc.strerror)


def _counted(path: str, rows: Iterator[Row]) -> Iterator[Row]:
    """``rows``, refused (InputError) at the step past MAX_STEPS."""
    for steps, row in enumerate(rows, 1):
        if steps > MAX_STEPS:
            raise InputError(path, "", "script of over %d steps" % MAX_STEPS)
        yield row


def _stdin_rows(names: Sequence[str], controllable: int) -> Iterator[Row]:
    """Standard input's rows, streamed as a file's are, whatever its length: the first
    errors.MAX_BYTES (and the line they end in) are held and checked before any row, as a file is
    checked whole, so a short script's bad line raises before the first row; past them a bad line
    raises when it is reached. What is held stays within MAX_BYTES."""
    stdin = sys.stdin.buffer
    held, count = bytearray(), 0
    while len(held) < MAX_BYTES:
        raw = stdin.readline(MAX_LINE_BYTES + 1)
        if not raw:
            break
        held += raw
        count += 1
    for _ in parse_lines(STDIN_NAME, handle_lines(STDIN_NAME, io.BytesIO(held)), names, controllable):
        pass
    lines = chain(handle_lines(STDIN_NAME, io.BytesIO(held)), handle_lines(STDIN_NAME, stdin, count + 1))
    return _counted(STDIN_NAME, parse_lines(STDIN_NAME, lines, names, controllable))


def read_script_rows(path: str, names: Sequence[str], controllable: int) -> Iterator[Row]:
    """A script's rows, to iterate once, in constant memory: a file (a regular file, as every
    input: :func:`~swarmvm.boundary.errors.open_input`) is read twice, line by line, first to
    refuse bad input (InputError, before any row) and MAX_STEPS or more steps, then for the rows;
    :data:`STDIN`, standard input, is streamed (:func:`_stdin_rows`)."""
    if path == STDIN:
        return _stdin_rows(names, controllable)
    for _ in _counted(path, parse_lines(path, file_lines(path), names, controllable)):
        pass
    return parse_lines(path, file_lines(path), names, controllable)


def script_lines(rows: Iterable[Iterable[int]], names: Sequence[str]) -> Iterator[str]:
    """Rows of event indices -> the script's lines, without newlines (events in index order),
    one at a time: a script of millions of steps is written in constant memory."""
    yield "# swarmvm event script: one step per line, the uncontrollable events that occur"
    for row in rows:
        yield " ".join("EV_" + names[e] for e in sorted(row)) or "-"


def format_script(rows: Iterable[Iterable[int]], names: Sequence[str]) -> str:
    """Rows of event indices -> script text."""
    return "".join(line + "\n" for line in script_lines(rows, names))


def random_rows(tables: Tables, steps: int, seed: int, density: float = 0.25) -> Iterator[Row]:
    """A reproducible random script over the model's uncontrollable events, row by row."""
    rng = random.Random(seed)
    uncontrollable = [e for e in range(tables.num_events) if not tables.controllable >> e & 1]
    for _ in range(steps):
        yield {e for e in uncontrollable if rng.random() < density}


def random_script(tables: Tables, steps: int, seed: int, density: float = 0.25) -> list[Row]:
    """The rows of :func:`random_rows` as a list."""
    return list(random_rows(tables, steps, seed, density))
