"""Load source automata as a set of local supervisors, one per file, each read by the reader
its suffix names (:data:`swarmvm.readers.READERS`).

Each file is one local supervisor whose alphabet is the events it declares. Controllability
and the ``public`` flag must agree between files that share an event; a ``probability``
attribute on transitions makes the set probabilistic (as Nadzoru 2's probabilistic plug-in)."""

import os
from collections.abc import Sequence
from fractions import Fraction

from ..boundary.errors import InputError
from ..compiler.model import LocalSupervisor, Supervisors
from . import read_automaton


def load_automata(paths: Sequence[str]) -> Supervisors:
    """Several automaton files -> one :class:`Supervisors` (one local supervisor per file)."""
    events: dict[str, tuple[bool, bool]] = {}      # name -> (controllable, public), as AutomatonFile's
    supervisors: list[LocalSupervisor] = []
    probabilistic, size = False, 0
    for path in paths:
        read = read_automaton(path)
        for name, flags in read.events.items():
            if name in events and events[name] != flags:
                what = "controllable" if events[name][0] != flags[0] else "public"
                raise InputError(path, what, "disagrees with an earlier file on this event", "event EV_%s" % name)
            events.setdefault(name, flags)
        supervisors.append(read.supervisor)
        probabilistic = probabilistic or read.probabilistic
        size += read.size_bytes
    if probabilistic:
        for supervisor in supervisors:
            for row in supervisor.states:
                for t in row:
                    if t.probability is None and events[t.event][0]:
                        t.probability = Fraction(1)
    names = list(events)
    return Supervisors(
        source="+".join(os.path.basename(p) for p in paths), events=names,
        controllable={n: events[n][0] for n in names}, public={n: events[n][1] for n in names},
        supervisors=supervisors, size_bytes=size, probabilistic=probabilistic)
