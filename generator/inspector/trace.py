"""Canonical traces (docs/conformance.md) read back for the inspector (docs/inspect.md).

Any runtime's trace has the same lines, ``STEP EVENTS STATES VIOLATIONS``, so one reader serves
the Python VM, the C host program, simavr and ARGoS alike. Every line is checked against the
supervisor set it is shown with (events it names, a state per supervisor, each in range, steps
numbered 1, 2, 3...), so a trace of another set is refused in one line rather than drawn wrong.

A swarm's run is millions of lines (200 robots x 20,000 steps), so reading is made of cheap
steps: a trace is read a block of bytes at a time (:data:`BLOCK`, whatever its length), and
each line becomes one number, its *step code* (:class:`Steps`: the distinct (states after,
events fired, violations added) of all the traces read, numbered). The text of a line after its
step number is parsed and checked the first time it is seen, and looked up afterwards (the
distinct texts are few: a supervisor set has few states and events), so a line costs a split,
a comparison of its step number with the text expected (:data:`STEP_TEXTS` of them made once
for all the traces) and a dictionary look-up; what is remembered is bounded (:data:`TAILS`).
A line is bytes, split on ASCII white space, and decoded only when it is checked in full; a
line whose step is not written as expected (a blank line, ``01``) is checked in full too. A run
keeps the codes of a window of steps in an array of machine integers (the page's size is
bounded: swarmvm.inspector.page); the steps outside it are read, checked and counted, for the
whole run's length, last states and violations and how often each event fired, and two traces
compared are read side by side, :data:`CHUNK` codes at a time (a pair of chunks with the same
codes from the same violation counters holds the same lines), so that where they differ is
found over the whole runs whatever window is kept (:func:`read_runs`)."""

from __future__ import annotations

from array import array
from collections import Counter
from dataclasses import dataclass, field
from itertools import islice, zip_longest
from typing import Iterator, Sequence

from ..boundary.errors import InputError, ascii_int, decode_text, open_input
from ..compiler.model import Model
from ..readers.event_script import MAX_LINE_BYTES

BLOCK = 1 << 20         # bytes of a trace read at a time
CHUNK = 1 << 16         # codes of two runs compared at a time
TAILS = 1 << 16         # line texts remembered at most (forgotten all at once when full)
STEP_TEXTS = 1 << 16    # step numbers' texts made once


class Numbering:
    """Distinct values numbered in order of first appearance (vectors of states, fired tuples)."""

    def __init__(self) -> None:
        self.numbers: dict[tuple[int, ...], int] = {}
        self.items: list[tuple[int, ...]] = []           # by number

    def __call__(self, value: tuple[int, ...]) -> int:
        number = self.numbers.setdefault(value, len(self.numbers))
        if number == len(self.items):
            self.items.append(value)
        return number

    def values(self) -> list[list[int]]:
        return [list(v) for v in self.items]


class Steps:
    """The distinct steps of the traces of one page, numbered (a step's code): the number of its
    vector of states after it (``vectors``; 0: every supervisor in state 0, the reset), of the
    events it fired in firing order (``fired``; 0: none) and the violations it added."""

    def __init__(self, model: Model) -> None:
        self.vectors, self.fired = Numbering(), Numbering()
        self.vectors(tuple(0 for _ in model.supervisors))
        self.fired(())
        self._codes: dict[tuple[int, int, int], int] = {}
        self.vector: list[int] = []      # per code
        self.events: list[int] = []      # per code, its number in ``fired``
        self.added: list[int] = []       # per code

    def code(self, vector: int, fired: int, added: int) -> int:
        key = (vector, fired, added)
        code = self._codes.get(key)
        if code is None:
            code = self._codes[key] = len(self.vector)
            self.vector.append(vector)
            self.events.append(fired)
            self.added.append(added)
        return code

    def __len__(self) -> int:
        return len(self.vector)


class TraceReader:
    """Reads the traces of one supervisor set into the codes of one :class:`Steps`, remembering
    what it parsed (a line's text after its step number, an EVENTS field, a STATES field) for
    every trace it reads."""

    def __init__(self, model: Model) -> None:
        self.steps = Steps(model)
        self._index = {"EV_" + e: i for i, e in enumerate(model.events)}
        self._sizes = [len(sup.states) for sup in model.supervisors]
        self._tails: dict[bytes, tuple[int, int]] = {}   # text after the step -> (code, violations)
        self._fired: dict[str, int] = {}
        self._vectors: dict[str, int] = {}
        self._texts: list[bytes] = []                    # _step_texts: n's text at n

    def chunks(self, path: str) -> Iterator[array[int]]:
        """The codes of the steps of the trace file at ``path``, a block of the file's lines at a
        time, checked as they are read; InputError (file, key ``trace``, ``line N``) at the first
        bad line."""
        number, due, violations, rest = 0, 1, 0, b""
        try:
            with open_input(path) as handle:
                while block := handle.read(BLOCK):
                    lines = (rest + block).split(b"\n")
                    rest = lines.pop()
                    if len(rest) >= MAX_LINE_BYTES:
                        lines.append(rest)              # refused when reached, after the lines before it
                    chunk = array("I")
                    due, violations = self._block(path, lines, number, due, violations, chunk)
                    number += len(lines)
                    yield chunk
        except OSError as exc:
            raise InputError(path, "", "cannot read file (%s)" % exc.strerror)
        if rest:                                        # a last line without its newline
            chunk = array("I")
            self._block(path, [rest], number, due, violations, chunk)
            yield chunk

    def _block(self, path: str, lines: list[bytes], number: int, due: int, violations: int,
               chunk: array[int]) -> tuple[int, int]:
        """The codes of ``lines`` (the first is line ``number + 1``, step ``due`` is expected)
        appended to ``chunk``: the step due next and the violation counter after them. A line is
        its step's expected text, then text already known good; any other is checked in full."""
        tails, steps, append, start = self._tails, self.steps, chunk.append, 0
        while start < len(lines):
            restart, first = len(lines), due
            for raw, text in zip(islice(lines, start, None), self._step_texts(due, len(lines) - start)):
                parts = raw.split(None, 1)
                known = None
                if len(parts) == 2 and parts[0] == text and len(raw) < MAX_LINE_BYTES:
                    known = tails.get(parts[1])
                if known is None:
                    known = self._line(path, number + start + due - first + 1, raw, due)
                    if known is None:                   # a blank line: the texts expected are one
                        restart = start + due - first + 1   # line off from here, start again
                        break
                code, after = known
                if after != violations:
                    code = steps.code(steps.vector[code], steps.events[code], after - violations)
                    violations = after
                append(code)
                due += 1
            start = restart
        return due, violations

    def _step_texts(self, due: int, count: int) -> list[bytes]:
        """Steps ``due`` .. ``due + count - 1`` as a trace writes them (the first STEP_TEXTS made
        once, for every trace)."""
        texts = self._texts
        if len(texts) < min(due + count, STEP_TEXTS):
            texts.extend(b"%d" % n for n in range(len(texts), min(due + count, STEP_TEXTS)))
        return texts[due:due + count] if due + count <= len(texts) else [b"%d" % n for n in range(due, due + count)]

    def _line(self, path: str, number: int, raw: bytes, due: int) -> tuple[int, int] | None:
        """A line whose text was not seen before, or whose step is not written as expected,
        checked in full: its code with no violation added and its violation counter, or None
        for a blank line. Its text is remembered only once it is known good."""
        where = "line %d" % number
        if len(raw) >= MAX_LINE_BYTES:
            raise InputError(path, where, "line over the %d-byte limit" % MAX_LINE_BYTES)
        decode_text(path, raw, where, " of the line")
        parts = [part.decode("utf-8") for part in raw.split()]
        if not parts:
            return None
        if len(parts) != 4:
            raise InputError(path, "trace", "not STEP EVENTS STATES VIOLATIONS", where)
        if ascii_int(parts[0]) != due:
            raise InputError(path, "trace", "step %s where step %d was due" % (parts[0], due), where)
        violations = ascii_int(parts[3])
        if violations is None:
            raise InputError(path, "trace", "violations %s is not a number" % parts[3], where)
        fired = self._fired.get(parts[1])
        if fired is None:
            fired = self._fired[parts[1]] = self.steps.fired(self._events(path, where, parts[1]))
        vector = self._vectors.get(parts[2])
        if vector is None:
            vector = self._vectors[parts[2]] = self.steps.vectors(self._states(path, where, parts[2]))
        known = self.steps.code(vector, fired, 0), violations
        if len(self._tails) >= TAILS:
            self._tails.clear()
        self._tails[raw.split(None, 1)[1]] = known
        return known

    def _events(self, path: str, where: str, text: str) -> tuple[int, ...]:
        if text == "-":
            return ()
        fired = []
        for name in text.split(","):
            event = self._index.get(name)
            if event is None and name.startswith("EV_"):
                event = ascii_int(name[3:], 3)           # an image without names prints EV_<index>
                event = event if event is not None and event < len(self._index) else None
            if event is None:
                raise InputError(path, "trace", "%s is not an event of the supervisors" % name, where)
            fired.append(event)
        return tuple(fired)

    def _states(self, path: str, where: str, text: str) -> tuple[int, ...]:
        parts = text.split(",")
        if len(parts) != len(self._sizes):
            raise InputError(path, "trace", "%d states for %d supervisors" % (len(parts), len(self._sizes)), where)
        states = []
        for sup, (part, size) in enumerate(zip(parts, self._sizes)):
            state = ascii_int(part)
            if state is None or state >= size:
                raise InputError(path, "trace", "supervisor %d has no state %s" % (sup, part), where)
            states.append(state)
        return tuple(states)


@dataclass
class Run:
    """One robot's trace: the codes of steps ``first`` .. ``first + len(codes) - 1`` (``start``:
    the vector of states before ``first``, and ``start_violations``), and the whole run's
    summary."""
    name: str
    first: int
    start: int = 0                                              # a vector's number (Steps.vectors)
    start_violations: int = 0
    codes: array[int] = field(default_factory=lambda: array("I"))   # per step kept, its code
    steps: int = 0                                              # steps in the whole trace
    counts: list[int] = field(default_factory=list)            # per event, how often it fired in the whole trace
    last: int = 0                                               # the vector after the last step
    last_violations: int = 0


class _Building:
    """A run read a chunk of codes at a time: the window's codes kept, every code counted."""

    def __init__(self, name: str, first: int, window: int, steps: Steps) -> None:
        self.run, self.steps, self.end = Run(name, first), steps, first - 1 + window
        self.counts: Counter[int] = Counter()      # per code, over the whole run
        self.before: Counter[int] = Counter()      # per code, before the window
        self.violations = 0                        # after the steps read so far

    def add(self, chunk: array[int]) -> None:
        run, read = self.run, self.run.steps
        low = min(len(chunk), max(0, run.first - 1 - read))          # the chunk's codes before the window
        high = min(len(chunk), max(0, self.end - read))              # ... and up to its end
        if low:
            self.before.update(chunk[:low])
            run.start = self.steps.vector[chunk[low - 1]]
        if high > low:
            run.codes.extend(chunk[low:high])
        counts = Counter(chunk)
        self.counts.update(counts)
        self.violations += sum(n * self.steps.added[code] for code, n in counts.items())
        run.steps += len(chunk)
        run.last = self.steps.vector[chunk[-1]] if chunk else run.last

    def done(self, path: str, events: int) -> Run:
        run, steps = self.run, self.steps
        if run.steps < run.first and run.steps:
            raise InputError(path, "trace", "has %d steps: nothing from step %d on" % (run.steps, run.first))
        run.start_violations = sum(n * steps.added[code] for code, n in self.before.items())
        run.last_violations = self.violations
        run.counts = [0] * events
        for code, n in self.counts.items():
            for event in steps.fired.items[steps.events[code]]:
                run.counts[event] += n
        return run


def _even(chunks: Iterator[array[int]]) -> Iterator[array[int]]:
    """``chunks`` regrouped in chunks of CHUNK codes (the last shorter)."""
    held: array[int] = array("I")
    for chunk in chunks:
        held.extend(chunk)
        while len(held) >= CHUNK:
            yield held[:CHUNK]
            del held[:CHUNK]
    if held:
        yield held


def _name(path: str) -> str:
    return path.replace("\\", "/").rsplit("/", 1)[-1]


@dataclass(frozen=True)
class Difference:
    """Where two whole runs differ: ``first``, the first step whose lines differ (a step one run
    has and the other has not differs), None if they are identical; ``steps``, how many steps
    differ in all; ``shown``, the first differing step among those a page keeps (None if none)."""
    first: int | None
    steps: int
    shown: int | None


@dataclass(frozen=True)
class Reading:
    """The traces of a page read: their steps' table, their runs (in the order given) and, two
    compared, where they differ."""
    steps: Steps
    runs: list[Run]
    difference: Difference | None


def read_runs(paths: Sequence[str], model: Model, first: int, window: int, compare: bool = False) -> Reading:
    """The trace files at ``paths``, each read once, line by line, checked against ``model``
    (InputError at the first bad line), steps ``first`` .. ``first + window - 1`` kept; with
    ``compare``, the two read side by side and where they differ found over the whole runs."""
    reader = TraceReader(model)
    building = [_Building(_name(path), first, window, reader.steps) for path in paths]
    if compare:
        difference = _compare(reader, (paths[0], paths[1]), (building[0], building[1]), first, window)
    else:
        difference = None
        for path, run in zip(paths, building):
            for chunk in reader.chunks(path):
                run.add(chunk)
    return Reading(reader.steps, [run.done(path, len(model.events)) for path, run in zip(paths, building)],
                   difference)


def _compare(reader: TraceReader, paths: tuple[str, str], runs: tuple[_Building, _Building], first: int,
             window: int) -> Difference:
    """Both traces read a chunk at a time; a pair of chunks with the same codes from the same
    violation counters holds the same lines, any other is compared line by line."""
    steps, empty = reader.steps, array("I")
    differ: int | None = None
    shown: int | None = None
    count = read = 0
    a, b = runs
    for one, two in zip_longest(*(_even(reader.chunks(path)) for path in paths), fillvalue=empty):
        x, y = a.violations, b.violations
        a.add(one)
        b.add(two)
        if one == two and x == y:
            read += CHUNK
            continue
        for offset, (p, q) in enumerate(zip_longest(one, two)):
            x += steps.added[p] if p is not None else 0
            y += steps.added[q] if q is not None else 0
            if p is None or q is None or x != y or (p != q and (steps.vector[p], steps.events[p]) !=
                                                    (steps.vector[q], steps.events[q])):
                step = read + offset + 1
                count += 1
                differ = step if differ is None else differ
                if shown is None and first <= step < first + window:
                    shown = step
        read += CHUNK
    return Difference(differ, count, shown)
