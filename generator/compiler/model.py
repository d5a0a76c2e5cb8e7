"""The data a loader produces (as read) and the canonical model the compiler works on."""

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Optional


@dataclass
class Transition:
    event: str                   # bare event name (no ``EV_`` prefix)
    target: int
    probability: Optional[Fraction] = None


@dataclass
class LocalSupervisor:
    """One local supervisor as read: states in file order, transitions in file order.

    ``marked`` holds the marked states of a source automaton (plants and specifications need
    them for non-blocking synthesis); None means every state is marked, as in a compiled
    supervisor, whose language is closed. The VM ignores marking."""
    alphabet: frozenset[str]
    initial: int
    states: list[list[Transition]]
    marked: Optional[frozenset[int]] = None


@dataclass
class Supervisors:
    """A whole input (one supervisor.yaml, or a set of automata), before canonicalisation."""
    source: str                  # file name(s) as given on the command line, basenames only
    events: list[str]            # bare names in input order
    controllable: dict[str, bool]
    public: dict[str, bool]
    supervisors: list[LocalSupervisor]
    size_bytes: int = 0
    probabilistic: bool = False
    warnings: list[str] = field(default_factory=list)
    # What the published VMs read of a supervisor.yaml beyond the model (docs/compat.md): each
    # event's name as written (``events`` holds swarmvm's names), each supervisor's
    # ``sup_current_state`` (the published VMs start there), the SHA-256 of the file's bytes.
    written: list[str] = field(default_factory=list)
    current: list[int] = field(default_factory=list)
    digest: bytes = b""
    # The events and states are in a supervisor file's order and numbering (a supervisor.yaml,
    # C tables, or an image packed from one), which the image's order section keeps for exact mode.
    file_order: bool = False

    def counts(self) -> tuple[int, int, int, int]:
        """Events, supervisors, states, transitions as read (the seed's KPI table counts)."""
        states = sum(len(s.states) for s in self.supervisors)
        transitions = sum(len(t) for s in self.supervisors for t in s.states)
        return len(self.events), len(self.supervisors), states, transitions


# A canonical transition: (event index, target state, probability or None).
CanonicalTransition = tuple[int, int, Optional[Fraction]]


@dataclass(frozen=True)
class CanonicalSupervisor:
    """States renumbered breadth-first from the initial state (which is 0); per state the
    transitions as (event index, target, probability or None), sorted by event index;
    ``input_states[i]`` is the input's number of state i (for the compatibility API's exact mode,
    which reports states as the input numbers them; not part of the model's identity)."""
    alphabet: frozenset[int]     # event indices
    states: tuple[tuple[CanonicalTransition, ...], ...]
    input_states: tuple[int, ...] = field(default=(), compare=False)
    start: int = field(default=0, compare=False)     # the input's current state, renumbered


@dataclass(frozen=True)
class Model:
    """Canonical supervisors: events sorted by name, identified by index into ``events``."""
    source: str
    events: tuple[str, ...]
    controllable: tuple[bool, ...]
    public: tuple[bool, ...]
    supervisors: tuple[CanonicalSupervisor, ...]
    probabilistic: bool
    warnings: tuple[str, ...] = field(default=(), compare=False)
