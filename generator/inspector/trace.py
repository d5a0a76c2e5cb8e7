"""Canonical traces (docs/conformance.md) read back for the inspector (docs/inspect.md).

Any runtime's trace has the same lines, ``STEP EVENTS STATES VIOLATIONS``, so one reader serves
the Python VM, the C host program, simavr and ARGoS alike. A trace is checked against the
supervisor set it is shown with (events it names, a state per supervisor, each in range, steps
numbered 1, 2, 3...), so a trace of another set is refused in one line rather than drawn wrong.

Only a window of steps is kept (the page's size is bounded: swarmvm.inspector.page); the whole
trace is still read, for its length, its last line and how often each event fired, and two
traces compared are read side by side so that where they differ is found over the whole runs
(:func:`compare_traces`), whatever window is kept."""

from dataclasses import dataclass, field
from itertools import zip_longest
from typing import Iterable, Iterator

from ..boundary.errors import InputError, ascii_int
from ..compiler.model import Model
from ..readers.event_script import file_lines

States = tuple[int, ...]        # one state per supervisor, as a trace line's STATES field
Fired = tuple[int, ...]         # event indices in firing order, as a trace line's EVENTS field


@dataclass
class Run:
    """One robot's trace: the steps ``first`` .. ``first + len(fired) - 1`` in full (``start``:
    the states before ``first``, and ``start_violations``), plus the whole run's summary."""
    name: str
    first: int
    start: States
    start_violations: int
    fired: list[Fired] = field(default_factory=list)     # per step, the events in firing order
    states: list[States] = field(default_factory=list)   # per step, the states after it
    violations: list[int] = field(default_factory=list)  # per step, the counter after it
    steps: int = 0                                       # steps in the whole trace
    counts: list[int] = field(default_factory=list)      # per event, how often it fired in the whole trace
    last: States = ()                                    # the states after the last step
    last_violations: int = 0


def _events(path: str, where: str, text: str, index: dict[str, int]) -> Fired:
    if text == "-":
        return ()
    fired = []
    for name in text.split(","):
        event = index.get(name)
        if event is None and name.startswith("EV_"):
            event = ascii_int(name[3:], 3)           # an image without names prints EV_<index>
            event = event if event is not None and event < len(index) else None
        if event is None:
            raise InputError(path, "trace", "%s is not an event of the supervisors" % name, where)
        fired.append(event)
    return tuple(fired)


def _states(path: str, where: str, text: str, sizes: list[int]) -> States:
    parts = text.split(",")
    if len(parts) != len(sizes):
        raise InputError(path, "trace", "%d states for %d supervisors" % (len(parts), len(sizes)), where)
    states = []
    for sup, (part, size) in enumerate(zip(parts, sizes)):
        state = ascii_int(part)
        if state is None or state >= size:
            raise InputError(path, "trace", "supervisor %d has no state %s" % (sup, part), where)
        states.append(state)
    return tuple(states)


Line = tuple[int, Fired, States, int]   # a trace line: step, events fired, states after, violations after


def trace_steps(path: str, lines: Iterable[str], model: Model) -> Iterator[Line]:
    """The steps of trace ``lines``, checked against ``model`` as they are read; InputError (file,
    key ``trace``, ``line N``) at the first bad line."""
    index = {"EV_" + e: i for i, e in enumerate(model.events)}
    sizes = [len(sup.states) for sup in model.supervisors]
    due = 1
    for number, line in enumerate(lines, 1):
        where = "line %d" % number
        parts = line.split()
        if not parts:
            continue
        if len(parts) != 4:
            raise InputError(path, "trace", "not STEP EVENTS STATES VIOLATIONS", where)
        step, violations = ascii_int(parts[0]), ascii_int(parts[3])
        if step is None or step != due:
            raise InputError(path, "trace", "step %s where step %d was due" % (parts[0], due), where)
        if violations is None:
            raise InputError(path, "trace", "violations %s is not a number" % parts[3], where)
        yield step, _events(path, where, parts[1], index), _states(path, where, parts[2], sizes), violations
        due += 1


def _new_run(name: str, model: Model, first: int) -> Run:
    run = Run(name, first, tuple(0 for _ in model.supervisors), 0, counts=[0] * len(model.events))
    run.last = run.start
    return run


def _keep(run: Run, line: Line, window: int) -> None:
    """One more step of ``run``: counted, and kept in full when in its window."""
    step, fired, states, violations = line
    for event in fired:
        run.counts[event] += 1
    if step < run.first:
        run.start, run.start_violations = states, violations
    elif step < run.first + window:
        run.fired.append(fired)
        run.states.append(states)
        run.violations.append(violations)
    run.steps, run.last, run.last_violations = step, states, violations


def _ended(path: str, run: Run) -> Run:
    if run.steps < run.first and run.steps:
        raise InputError(path, "trace", "has %d steps: nothing from step %d on" % (run.steps, run.first))
    return run


def parse_trace(path: str, name: str, lines: Iterable[str], model: Model, first: int, window: int) -> Run:
    """The run of trace ``lines``, checked against ``model``, steps ``first`` .. ``first +
    window - 1`` kept in full; InputError (file, key ``trace``, ``line N``) at the first bad line."""
    run = _new_run(name, model, first)
    for line in trace_steps(path, lines, model):
        _keep(run, line, window)
    return _ended(path, run)


def _name(path: str) -> str:
    return path.replace("\\", "/").rsplit("/", 1)[-1]


def read_trace(path: str, model: Model, first: int, window: int) -> Run:
    """The trace file at ``path`` (:func:`parse_trace`), named by its file name, read line by line."""
    return parse_trace(path, _name(path), file_lines(path), model, first, window)


@dataclass(frozen=True)
class Difference:
    """Where two whole runs differ: ``first``, the first step whose lines differ (a step one run
    has and the other has not differs), None if they are identical; ``steps``, how many steps
    differ in all; ``shown``, the first differing step among those a page keeps (None if none)."""
    first: int | None
    steps: int
    shown: int | None


def compare_traces(paths: tuple[str, str], model: Model, first: int, window: int) -> tuple[list[Run], Difference]:
    """Two trace files read side by side, each once, line by line (:func:`parse_trace`): their
    runs, steps ``first`` .. ``first + window - 1`` kept in full, and where they differ over the
    whole runs, whatever window is kept."""
    runs = [_new_run(_name(path), model, first) for path in paths]
    differ: int | None = None
    shown: int | None = None
    count = 0
    for a, b in zip_longest(*(trace_steps(path, file_lines(path), model) for path in paths)):
        for run, line in zip(runs, (a, b)):
            if line is not None:
                _keep(run, line, window)
        if a != b:
            step = (a or b)[0]
            count += 1
            differ = step if differ is None else differ
            if shown is None and first <= step < first + window:
                shown = step
    return [_ended(path, run) for path, run in zip(paths, runs)], Difference(differ, count, shown)


def first_difference(a: Run, b: Run) -> int | None:
    """The first step (numbered as in the traces) where two runs' lines differ, within the
    steps both keep, or where one ends first; None if the kept steps are identical (the whole
    runs: :func:`compare_traces`)."""
    for offset, (one, two) in enumerate(zip(zip(a.fired, a.states, a.violations), zip(b.fired, b.states,
                                                                                       b.violations))):
        if one != two:
            return a.first + offset
    if len(a.fired) != len(b.fired):
        return a.first + min(len(a.fired), len(b.fired))
    return None
