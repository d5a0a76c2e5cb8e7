"""The canonical form (generator/compiler/canonical.py) pinned where `make mutation` found it unpinned
(issue 29, docs/mutation.md): the unreachable-states warning on both sides of its 20-state cut
and its absence when every state is reached, and the search from the input's current state when
the initial state does not reach it."""

import pytest

from swarmvm.compiler.canonical import canonicalise
from swarmvm.compiler.model import LocalSupervisor, Supervisors, Transition


def one_supervisor(states, initial=0, current=None):
    """One supervisor over the event "a"; ``states[i]`` lists the targets of state i's
    transitions on "a" (a list, so that a test can give a state no transition)."""
    rows = [[Transition("a", target) for target in targets] for targets in states]
    return Supervisors(source="s.yaml", events=["a"], controllable={"a": True}, public={"a": False},
                       supervisors=[LocalSupervisor(frozenset({"a"}), initial, rows)],
                       current=[] if current is None else [current])


def test_a_supervisor_whose_states_are_all_reached_gives_no_warning():
    assert canonicalise(one_supervisor([[1], [0]])).warnings == ()


TWENTY = ", ".join(str(s) for s in range(1, 21))


@pytest.mark.parametrize("dropped,shown", [(20, TWENTY), (21, TWENTY + ", ...")], ids=["20", "21"])
def test_the_warning_names_20_unreachable_states_and_marks_more(dropped, shown):
    """State 0 loops on itself; states 1..dropped, each looping on itself, are never reached."""
    model = canonicalise(one_supervisor([[s] for s in range(dropped + 1)]))
    assert model.warnings == ("s.yaml: supervisor 0: %d unreachable state(s) dropped (states %s)" % (dropped, shown),)


def test_the_current_state_and_what_it_reaches_are_kept_after_the_initial_states_search():
    """Initial 0 reaches 1 only; the current state 2 reaches 3; 4 is reached by neither. Breadth
    first from 0 (0, 1), then from 2 (2, 3): 4 dropped, the start renumbered 2."""
    model = canonicalise(one_supervisor([[1], [1], [3], [2], [0]], initial=0, current=2))
    supervisor = model.supervisors[0]
    assert supervisor.input_states == (0, 1, 2, 3) and supervisor.start == 2
    assert supervisor.states == (((0, 1, None),), ((0, 1, None),), ((0, 3, None),), ((0, 2, None),))
    assert model.warnings == ("s.yaml: supervisor 0: 1 unreachable state(s) dropped (states 4)",)


def test_without_a_current_state_the_search_starts_from_the_initial_state_alone():
    """An input with no current state (automata, not a supervisor.yaml) starts where it begins."""
    model = canonicalise(one_supervisor([[0], [1]], initial=1))
    assert model.supervisors[0].input_states == (1,) and model.supervisors[0].start == 0
