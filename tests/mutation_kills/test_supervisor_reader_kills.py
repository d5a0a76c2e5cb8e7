"""The supervisor.yaml reader (generator/readers/supervisor_yaml.py) pinned where `make mutation` found it
unpinned (issue 29, docs/mutation.md): each refusal's exact one line (file, key, where, message),
the bounds on both sides (a probability of 0 and of 1, a target byte of 255 and of 256, a current
state one under and at the number of states, a value shown whole at 60 characters and cut at 61),
the target of a state numbered 256 and over (hi * 256 + lo, in a supervisor of 258 states), the
probability blocks of three supervisors read each from its own position, published mode (its
warning for a state's second transition on an event, read on after it) against the default one;
and a bug found on the way: a probability position past the end of sup_data_prob, a traceback
(IndexError) before it was refused as out of range."""

from fractions import Fraction

import pytest
import yaml

from swarmvm.boundary.errors import InputError
from swarmvm.readers.supervisor_yaml import load_supervisor

# Two events, a (controllable) and b; one supervisor of two states: 0 -a-> 1, 0 -b-> 0, 1 -b-> 0.
DATA = [2, "EV_a", 0, 1, "EV_b", 0, 0, 1, "EV_b", 0, 0]
BASE = {"num_events": 2, "num_supervisors": 1, "events": ["EV_a", "EV_b"], "ev_controllable": [1, 0],
        "sup_events": [[1, 1]], "sup_init_state": [0], "sup_data_pos": [0], "sup_data": DATA}


class _PlainDumper(yaml.SafeDumper):
    """Every value written out where it is used: the reader refuses aliases (``[[1, 1]] * 2``
    would otherwise be written as an anchor and an alias)."""

    def ignore_aliases(self, data):
        return True


def written(tmp_path, **keys):
    """A supervisor.yaml of BASE with ``keys`` replacing or adding keys (None removes one)."""
    doc = {key: value for key, value in {**BASE, **keys}.items() if value is not None}
    path = tmp_path / "supervisor.yaml"
    path.write_text(yaml.dump(doc, Dumper=_PlainDumper, default_flow_style=None, sort_keys=False))
    return path


def refusal(path):
    """The one line InputError renders for ``path``, read in the default (strict) mode."""
    with pytest.raises(InputError) as refused:
        load_supervisor(str(path))
    return str(refused.value)


def test_the_base_file_loads(tmp_path):
    """The files below are this one with one thing wrong: it must load as its comment says, its
    events private (no ev_shared or ev_public key) and it not probabilistic."""
    spec = load_supervisor(str(written(tmp_path)))
    states = spec.supervisors[0].states
    assert [[(t.event, t.target) for t in state] for state in states] == [[("a", 1), ("b", 0)], [("b", 0)]]
    assert spec.events == ["a", "b"] and spec.controllable == {"a": True, "b": False}
    assert spec.public == {"a": False, "b": False} and not spec.probabilistic


# -- values: probabilities, the shown value, line numbers --------------------------------------------------

@pytest.mark.parametrize("text, value", [("0", Fraction(0)), ("0.0", Fraction(0)), ("1", Fraction(1)),
                                         ("1/4", Fraction(1, 4))])
def test_a_probability_of_0_or_1_is_read(tmp_path, text, value):
    path = written(tmp_path, sup_data_prob_pos=[0], sup_data_prob=[1, text, 0])
    assert load_supervisor(str(path)).supervisors[0].states[0][0].probability == value


@pytest.mark.parametrize("text", ["1.01", "2/1"])
def test_a_probability_over_1_is_refused(tmp_path, text):
    path = written(tmp_path, sup_data_prob_pos=[0], sup_data_prob=[1, text, 0])
    assert refusal(path) == "%s: sup_data_prob[1]: supervisor 0, state 0, event EV_a: %s is not a probability in [0, 1]" % (
        path, text)


@pytest.mark.parametrize("length, shown", [(60, "-" * 60), (61, "-" * 57 + "...")])
def test_a_value_is_shown_whole_up_to_60_characters_then_cut_to_57_and_dots(tmp_path, length, shown):
    path = written(tmp_path, events=["-" * length, "EV_b"])
    assert refusal(path) == "%s: events[0]: %s is not an event name (at most 255 letters, digits and '_')" % (path, shown)


@pytest.mark.parametrize("text, line", [("\nnum_events: 1\n\x01", 3), ("\n\nnum_events: \x01\nnum_supervisors: 1\n", 3),
                                        ("\x01", 1)])
def test_a_character_yaml_does_not_allow_is_refused_naming_its_line(tmp_path, text, line):
    """The line counts the newlines from the file's first character on (a file that starts with
    an empty line included)."""
    path = tmp_path / "supervisor.yaml"
    path.write_text(text)
    assert refusal(path) == "%s: not valid YAML at line %d: character #x0001 is not allowed" % (path, line)


@pytest.mark.parametrize("key", ["num_events", "num_supervisors"])
def test_no_events_or_no_supervisors_is_refused(tmp_path, key):
    path = written(tmp_path, **{key: 0})
    assert refusal(path) == "%s: %s: value 0 out of range (must be in 1..255)" % (path, key)


def test_one_event_and_one_supervisor_are_enough(tmp_path):
    path = written(tmp_path, num_events=1, events=["EV_a"], ev_controllable=[1], sup_events=[[1]],
                   sup_data=[1, "EV_a", 0, 0])
    spec = load_supervisor(str(path))
    assert spec.events == ["a"] and len(spec.supervisors) == 1


# -- sup_events, sup_current_state ---------------------------------------------------------------------------

@pytest.mark.parametrize("row", [[1], [1, 1, 1], "1"])
def test_a_sup_events_row_of_the_wrong_length_is_refused(tmp_path, row):
    path = written(tmp_path, sup_events=[row])
    assert refusal(path) == "%s: sup_events[0]: supervisor 0: expected a list of 2 flags (num_events)" % path


def test_without_sup_current_state_each_supervisor_starts_in_its_initial_state(tmp_path):
    spec = load_supervisor(str(written(tmp_path, sup_init_state=[1])))
    assert spec.current == [1] and spec.supervisors[0].initial == 1


@pytest.mark.parametrize("current", [0, 1])
def test_sup_current_state_is_read_up_to_the_last_state(tmp_path, current):
    spec = load_supervisor(str(written(tmp_path, sup_init_state=[1 - current], sup_current_state=[current])))
    assert spec.current == [current] and spec.supervisors[0].initial == 1 - current


def test_a_current_state_past_the_last_is_refused(tmp_path):
    path = written(tmp_path, sup_current_state=[2])
    assert refusal(path) == "%s: sup_current_state[0]: supervisor 0: value 2 out of range (must be in 0..1)" % path


# -- sup_data_pos and the blocks of sup_data -----------------------------------------------------------------

@pytest.mark.parametrize("start", [12, 100])
def test_a_block_starting_past_the_end_of_sup_data_is_refused(tmp_path, start):
    path = written(tmp_path, sup_data_pos=[start])
    assert refusal(path) == ("%s: sup_data_pos[0]: supervisor 0: position %d does not start a block inside sup_data "
                             "(11 entries)" % (path, start))


@pytest.mark.parametrize("positions, s", [([11], 0), ([0, 0], 0), ([0, 11], 1)])
def test_a_block_starting_where_it_ends_is_a_supervisor_without_states(tmp_path, positions, s):
    """A block from sup_data_pos[s] to the next position (or the end of sup_data) that is empty:
    a position inside sup_data, or just past its end, with no states in it."""
    path = written(tmp_path, num_supervisors=len(positions), sup_events=[[1, 1]] * len(positions),
                   sup_init_state=[0] * len(positions), sup_data_pos=positions)
    assert refusal(path) == "%s: sup_data_pos[%d]: supervisor %d: supervisor has no states" % (path, s, s)


@pytest.mark.parametrize("data", [[1, "EV_a", 0], [1, "EV_a", 0, 0, 1, "EV_a", 0]])
def test_a_block_one_entry_short_of_its_last_transition_is_refused(tmp_path, data):
    path = written(tmp_path, sup_data=data)
    state = 0 if len(data) == 3 else 1
    assert refusal(path) == ("%s: sup_data: supervisor 0, state %d: the block of supervisor 0 does not end where "
                             "sup_data ends" % (path, state))


def test_a_block_running_one_entry_into_the_next_supervisors_is_refused(tmp_path):
    path = written(tmp_path, num_supervisors=2, sup_events=[[1, 1], [1, 1]], sup_init_state=[0, 0],
                   sup_data_pos=[0, 3], sup_data=[1, "EV_a", 0, 0, 1, "EV_b", 0, 0])
    assert refusal(path) == ("%s: sup_data_pos[1]: supervisor 0, state 0: the block of supervisor 0 does not end "
                             "where the next supervisor starts (sup_data[3])" % path)


@pytest.mark.parametrize("name, shown", [(["EV_a"], "a list"), ({"EV_a": 1}, "a mapping"), ("EV_a-b", "EV_a-b")])
def test_a_transition_event_that_is_not_a_name_is_refused(tmp_path, name, shown):
    path = written(tmp_path, sup_data=[1, name, 0, 0])
    assert refusal(path) == "%s: sup_data[1]: supervisor 0, state 0: %s is not an event name" % (path, shown)


# -- target bytes and states numbered from 256 on ------------------------------------------------------------

@pytest.mark.parametrize("hi, lo, key, message", [
    (256, 0, 2, "value 256 out of range (must be in 0..255)"),
    (0, 256, 3, "value 256 out of range (must be in 0..255)"),
    (255, 0, 2, "target 65280 out of range (the supervisor has 1 states)"),
    (0, 255, 2, "target 255 out of range (the supervisor has 1 states)"),
    (1, 0, 2, "target 256 out of range (the supervisor has 1 states)"),
    (1, 1, 2, "target 257 out of range (the supervisor has 1 states)"),
])
def test_a_target_byte_over_255_or_a_target_past_the_last_state_is_refused(tmp_path, hi, lo, key, message):
    """The byte bound refuses 256 and takes 255 (which then names a state that is not there);
    the target refusal names the hi byte's entry and hi * 256 + lo."""
    path = written(tmp_path, sup_data=[1, "EV_a", hi, lo])
    assert refusal(path) == "%s: sup_data[%d]: supervisor 0, state 0, event EV_a: %s" % (path, key, message)


def test_targets_of_states_256_and_over_are_hi_times_256_plus_lo(tmp_path):
    """A ring of 258 states, q -a-> q + 1 and the last back to 0: the targets 256 and 257 take
    the hi byte."""
    n = 258
    data = [entry for q in range(n) for entry in (1, "EV_a", (q + 1) % n // 256, (q + 1) % n % 256)]
    path = written(tmp_path, sup_data=data)
    states = load_supervisor(str(path)).supervisors[0].states
    assert [state[0].target for state in states] == [(q + 1) % n for q in range(n)]


def test_by_default_a_second_transition_on_an_event_is_refused(tmp_path):
    path = written(tmp_path, sup_data=[2, "EV_a", 0, 1, "EV_a", 0, 0, 0])
    assert refusal(path) == ("%s: sup_data[4]: supervisor 0, state 0, event EV_a: nondeterministic: a second "
                             "transition on this event from this state" % path)


def test_by_default_an_event_name_of_other_visible_characters_is_refused(tmp_path):
    """``go-on`` is a name only in published mode (there it is ``go_on``)."""
    path = written(tmp_path, events=["EV_a", "EV_go-on"],
                   sup_data=[2, "EV_a", 0, 1, "EV_go-on", 0, 0, 1, "EV_go-on", 0, 0])
    assert refusal(path) == ("%s: events[1]: EV_go-on is not an event name (at most 255 letters, digits and '_')"
                             % path)
    assert load_supervisor(str(path), published=True).events == ["a", "go_on"]


def test_published_mode_keeps_the_first_of_two_transitions_on_an_event_and_says_so(tmp_path):
    path = written(tmp_path, sup_data=[2, "EV_a", 0, 1, "EV_a", 0, 0, 0])
    spec = load_supervisor(str(path), published=True)
    assert [(t.event, t.target) for t in spec.supervisors[0].states[0]] == [("a", 1)]
    assert spec.warnings == ["%s: sup_data[4]: supervisor 0, state 0, event EV_a: a second transition on this event "
                             "from this state; the first is kept, as the published VMs' search finds it" % path]


def test_published_mode_reads_on_after_a_dropped_transition(tmp_path):
    """The state's transitions after the dropped one are kept, and the next state read."""
    path = written(tmp_path, sup_data=[3, "EV_a", 0, 1, "EV_a", 0, 0, "EV_b", 0, 0, 1, "EV_b", 0, 0])
    states = load_supervisor(str(path), published=True).supervisors[0].states
    assert [[(t.event, t.target) for t in state] for state in states] == [[("a", 1), ("b", 0)], [("b", 0)]]


# -- probability blocks --------------------------------------------------------------------------------------

def three_supervisors(tmp_path, prob_pos, prob):
    """Three supervisors of one state each, a self-loop on the controllable a; their probability
    blocks at ``prob_pos`` in ``prob``."""
    return written(tmp_path, num_supervisors=3, sup_events=[[1, 1]] * 3, sup_init_state=[0] * 3,
                   sup_data_pos=[0, 4, 8], sup_data=[1, "EV_a", 0, 0] * 3,
                   sup_data_prob_pos=prob_pos, sup_data_prob=prob)


def test_each_supervisors_probabilities_are_read_from_its_own_block(tmp_path):
    path = three_supervisors(tmp_path, [0, 2, 4], [1, "1/2", 1, "1/3", 1, "1/4"])
    probabilities = [s.states[0][0].probability for s in load_supervisor(str(path)).supervisors]
    assert probabilities == [Fraction(1, 2), Fraction(1, 3), Fraction(1, 4)]


@pytest.mark.parametrize("prob_pos, prob, key, s", [
    ([0, 3, 5], [1, "1/2", 0, 1, "1/3", 1, "1/4"], "sup_data_prob_pos[1]", 0),
    ([0, 2, 5], [1, "1/2", 1, "1/3", 0, 1, "1/4"], "sup_data_prob_pos[2]", 1),
    ([0, 2, 4], [1, "1/2", 1, "1/3", 1, "1/4", 0], "sup_data_prob", 2),
])
def test_a_probability_block_ending_before_the_next_is_refused_naming_the_next_position(tmp_path, prob_pos, prob,
                                                                                        key, s):
    path = three_supervisors(tmp_path, prob_pos, prob)
    assert refusal(path) == ("%s: %s: supervisor %d: the probability block of supervisor %d does not end where the "
                             "next starts" % (path, key, s, s))


def test_a_probability_block_ending_inside_a_state_is_refused(tmp_path):
    path = written(tmp_path, ev_controllable=[1, 1], sup_data_prob_pos=[0], sup_data_prob=[2, "1/2"])
    assert refusal(path) == ("%s: sup_data_prob: supervisor 0, state 0, event EV_b: block ends inside a state's "
                             "probabilities" % path)


@pytest.mark.parametrize("prob_pos, where", [([0, 100, 4], "supervisor 1"), ([0, 2, 100], "supervisor 2")])
def test_a_probability_position_past_the_end_of_sup_data_prob_is_refused(tmp_path, prob_pos, where):
    """Found here: a supervisor's block running on to a next position past the end of
    sup_data_prob was read on past it (an IndexError, a traceback instead of one line)."""
    path = three_supervisors(tmp_path, prob_pos, [1, "1/2", 1, "1/3", 1, "1/4"])
    key = "sup_data_prob_pos[%d]" % prob_pos.index(100)
    assert refusal(path) == "%s: %s: %s: value 100 out of range (must be in 0..6)" % (path, key, where)


@pytest.mark.parametrize("last, message", [
    (4, "sup_data_prob: supervisor 2, state 0: block ends before the supervisor's last state"),
    (5, "sup_data_prob_pos[2]: supervisor 2: value 5 out of range (must be in 0..4)"),
])
def test_a_probability_position_may_be_the_length_of_sup_data_prob_and_no_more(tmp_path, last, message):
    """The last supervisor's block at the end of sup_data_prob is empty (refused where its first
    state is read); one past the end is a position out of range."""
    path = three_supervisors(tmp_path, [0, 2, last], [1, "1/2", 1, "1/3"])
    assert refusal(path) == "%s: %s" % (path, message)
