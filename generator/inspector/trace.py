"""Canonical traces (docs/conformance.md) read back for the inspector (docs/inspect.md).

Any runtime's trace has the same lines, ``STEP EVENTS STATES VIOLATIONS``, so one reader serves
the Python VM, the C host program, simavr and ARGoS alike. A trace is checked against the
supervisor set it is shown with (events it names, a state per supervisor, each in range, steps
numbered 1, 2, 3...), so a trace of another set is refused in one line rather than drawn wrong.

Only a window of steps is kept (the page's size is bounded: swarmvm.inspector.page); the whole
trace is still read, for its length, its last line and how often each event fired."""

from dataclasses import dataclass, field
from typing import Iterable

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


def parse_trace(path: str, name: str, lines: Iterable[str], model: Model, first: int, window: int) -> Run:
    """The run of trace ``lines``, checked against ``model``, steps ``first`` .. ``first +
    window - 1`` kept in full; InputError (file, key ``trace``, ``line N``) at the first bad line."""
    index = {"EV_" + e: i for i, e in enumerate(model.events)}
    sizes = [len(sup.states) for sup in model.supervisors]
    run = Run(name, first, tuple(0 for _ in sizes), 0, counts=[0] * len(model.events))
    run.last = run.start
    for number, line in enumerate(lines, 1):
        where = "line %d" % number
        parts = line.split()
        if not parts:
            continue
        if len(parts) != 4:
            raise InputError(path, "trace", "not STEP EVENTS STATES VIOLATIONS", where)
        step, violations = ascii_int(parts[0]), ascii_int(parts[3])
        if step is None or step != run.steps + 1:
            raise InputError(path, "trace", "step %s where step %d was due" % (parts[0], run.steps + 1), where)
        if violations is None:
            raise InputError(path, "trace", "violations %s is not a number" % parts[3], where)
        fired, states = _events(path, where, parts[1], index), _states(path, where, parts[2], sizes)
        for event in fired:
            run.counts[event] += 1
        if step < first:
            run.start, run.start_violations = states, violations
        elif step < first + window:
            run.fired.append(fired)
            run.states.append(states)
            run.violations.append(violations)
        run.steps, run.last, run.last_violations = step, states, violations
    if run.steps < first and run.steps:
        raise InputError(path, "trace", "has %d steps: nothing from step %d on" % (run.steps, first))
    return run


def read_trace(path: str, model: Model, first: int, window: int) -> Run:
    """The trace file at ``path`` (:func:`parse_trace`), named by its file name, read line by line."""
    return parse_trace(path, path.replace("\\", "/").rsplit("/", 1)[-1], file_lines(path), model, first, window)


def first_difference(a: Run, b: Run) -> int | None:
    """The first step (numbered as in the traces) where two runs' lines differ, within the
    steps both keep, or where one ends first; None if the kept steps are identical."""
    for offset, (one, two) in enumerate(zip(zip(a.fired, a.states, a.violations), zip(b.fired, b.states,
                                                                                       b.violations))):
        if one != two:
            return a.first + offset
    if len(a.fired) != len(b.fired):
        return a.first + min(len(a.fired), len(b.fired))
    return None
