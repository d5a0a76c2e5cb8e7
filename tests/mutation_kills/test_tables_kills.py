"""The VM tables (generator/compiler/tables.py) pinned where `make mutation` found them unpinned (issue 29,
docs/mutation.md): each transition's Q15 probability, by a known answer on both kinds of event,
and the tables fixed once built."""

import dataclasses
from fractions import Fraction

import pytest

from swarmvm.compiler.model import CanonicalSupervisor, Model
from swarmvm.compiler.tables import build_tables


def probabilistic_model():
    """State 0: the controllable "a" with probability 1/4 and without, the uncontrollable "b"
    with a probability (ignored: only controllable events are drawn)."""
    states = (((0, 0, Fraction(1, 4)), (1, 1, Fraction(1, 3))), ((0, 0, None),))
    return Model(source="p.yaml", events=("a", "b"), controllable=(True, False), public=(False, False),
                 supervisors=(CanonicalSupervisor(frozenset({0, 1}), states),), probabilistic=True)


def test_a_controllable_events_probability_is_its_q15_and_every_other_transition_q15_one():
    assert build_tables(probabilistic_model()).probs == (8192, 32768, 32768)


def test_tables_are_fixed_once_built():
    """Every target writes from the same Tables: none can change them for the targets after it."""
    tables = build_tables(probabilistic_model())
    assert hash(tables) == hash(build_tables(probabilistic_model()))
    with pytest.raises(dataclasses.FrozenInstanceError):
        tables.num_events = 3
