"""The VM tables every target shares, built once from the canonical model.

Per supervisor: its alphabet as an event mask, the global index of its first state, its state
count and initial state. Per state: the mask of events it has a transition on (``defined``)
and the index of its first successor in ``targets``. The successor on event e is
``targets[first + rank]`` where rank counts the defined events below e: a step needs no
search, only mask operations, whatever the size of the automata."""

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from math import floor
from typing import Optional

from .model import Model
from .runtime_files import image_format


@dataclass(frozen=True)
class Tables:
    num_events: int
    num_supervisors: int
    mask_bytes: int
    state_width: int
    controllable: int
    public: int
    sup_alphabet: tuple[int, ...]
    sup_first_state: tuple[int, ...]
    sup_num_states: tuple[int, ...]
    sup_initial: tuple[int, ...]
    state_defined: tuple[int, ...]
    state_first: tuple[int, ...]
    targets: tuple[int, ...]
    probs: Optional[tuple[int, ...]]
    names: tuple[str, ...]

    @property
    def num_states(self) -> int:
        return len(self.state_defined)

    @property
    def num_transitions(self) -> int:
        return len(self.targets)


def q15(probability: Fraction | float | str) -> int:
    """A probability as an unsigned Q15 fixed-point number (1.0 = the format's Q15_ONE), rounded
    half up."""
    one: int = image_format().Q15_ONE
    return min(one, floor(Fraction(probability) * one + Fraction(1, 2)))


def state_width(widest: int) -> int:
    """Bytes of a target state number for supervisors of at most ``widest`` states: the
    narrowest of the format's STATE_WIDTHS that numbers them all (the widest when none does:
    so many states are over the format's MAX_STATES, which packing refuses)."""
    widths: tuple[int, ...] = image_format().STATE_WIDTHS
    return next((width for width in widths if widest <= 1 << 8 * width), widths[-1])


def _mask(indices: Iterable[int]) -> int:
    value = 0
    for i in indices:
        value |= 1 << i
    return value


def build_tables(model: Model) -> Tables:
    """:class:`~swarmvm.compiler.model.Model` -> :class:`Tables`."""
    sup_first: list[int] = []
    sup_count: list[int] = []
    defined: list[int] = []
    first: list[int] = []
    targets: list[int] = []
    probs: list[int] = []
    one: int = image_format().Q15_ONE
    for sup in model.supervisors:
        sup_first.append(len(defined))
        sup_count.append(len(sup.states))
        for row in sup.states:
            defined.append(_mask(e for e, _, _ in row))
            first.append(len(targets))
            for e, target, p in row:
                targets.append(target)
                probs.append(one if p is None or not model.controllable[e] else q15(p))
    return Tables(
        num_events=len(model.events), num_supervisors=len(model.supervisors),
        mask_bytes=(len(model.events) + 7) // 8, state_width=state_width(max(sup_count)),
        controllable=_mask(i for i, c in enumerate(model.controllable) if c),
        public=_mask(i for i, p in enumerate(model.public) if p),
        sup_alphabet=tuple(_mask(s.alphabet) for s in model.supervisors),
        sup_first_state=tuple(sup_first), sup_num_states=tuple(sup_count),
        sup_initial=tuple(0 for _ in model.supervisors),
        state_defined=tuple(defined), state_first=tuple(first), targets=tuple(targets),
        probs=tuple(probs) if model.probabilistic else None, names=model.events)
