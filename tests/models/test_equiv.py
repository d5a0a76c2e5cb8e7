"""swarmvm equiv: same events and same language of the conjunction, up to state renaming and
split into local supervisors; a shortest distinguishing sequence otherwise. libFAUDES'
LanguageEquality on the conjunctions is the oracle."""

import itertools
from dataclasses import replace

import faudes
import pytest

from models.model_cases import CORPUS, ENERGY_WORKER, SUPERVISORS, conjunction, run
from swarmvm.models.equivalence import compare
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.models.product import Conjunction


def model(path):
    return compile_inputs([str(path)]).model


def accepts(m, word):
    """``word`` is in m's closed language (over m's own events: any other event is not)."""
    vector, conjunction = tuple(0 for _ in m.supervisors), Conjunction.of(m)
    for name in word:
        if name not in m.events:
            return False
        vector = conjunction.step(vector, m.events.index(name))
        if vector is None:
            return False
    return True


def test_a_set_is_equivalent_to_its_source_automata_in_a_directory(tmp_path):
    for path in sorted((CORPUS / "automata").glob("energy_worker_Sloc?.xml")):
        (tmp_path / path.name).write_bytes(path.read_bytes())
    result = run("equiv", ENERGY_WORKER, tmp_path)
    assert result.exit_code == 0 and result.stdout.startswith("equivalent")
    result = run("equiv", ENERGY_WORKER, tmp_path / "energy_worker_Sloc1.xml")
    assert result.exit_code == 1          # one local supervisor is not the whole set


def test_a_removed_transition_is_found_with_a_shortest_sequence(tmp_path):
    text = ENERGY_WORKER.read_text()
    # Supervisor 0's state 1 (in file order): moveToWork now loops back instead of moving on.
    changed = text.replace("3,EV_highEnergy,0,1,EV_moveToWork,0,2,EV_lowEnergy,0,0",
                           "3,EV_highEnergy,0,1,EV_moveToWork,0,1,EV_lowEnergy,0,0", 1)
    assert changed != text
    path = tmp_path / "changed.yaml"
    path.write_text(changed)
    result = run("equiv", ENERGY_WORKER, path)
    assert result.exit_code == 1
    lines = result.stdout.splitlines()
    assert lines[0] == "not equivalent: the conjunctions' languages differ"
    word = lines[1].split(": ", 1)[1].split(" (")[0].split()
    names = [w[3:] for w in word]
    a, b = model(ENERGY_WORKER), model(path)
    if accepts(b, names):
        a, b = b, a
        assert lines[1].endswith("(allowed by %s, not by %s)" % (path, ENERGY_WORKER))
    else:
        assert lines[1].endswith("(allowed by %s, not by %s)" % (ENERGY_WORKER, path))
    assert accepts(a, names) and not accepts(b, names) and accepts(b, names[:-1])
    # Shortest: no shorter word tells them apart (checked by brute force over all words).
    alphabet = list(a.events)
    for n in range(len(names)):
        for shorter in itertools.product(alphabet, repeat=n):
            assert accepts(a, shorter) == accepts(b, shorter)
    assert not faudes.LanguageEquality(conjunction(a), conjunction(b))


def test_different_events_or_flags_are_reported(tmp_path):
    result = run("equiv", ENERGY_WORKER, CORPUS / "openswarm" / "uav.yaml")
    assert result.exit_code == 1 and result.stdout.startswith("not equivalent: events in only one set: EV_")
    flipped = tmp_path / "flipped.yaml"
    flipped.write_text(ENERGY_WORKER.read_text().replace("ev_controllable: [ 1,1,0", "ev_controllable: [ 1,1,1", 1))
    result = run("equiv", ENERGY_WORKER, flipped)
    assert result.stdout == ("not equivalent: EV_highEnergy is controllable in one set only (the conjunctions' "
                             "languages are the same: no event sequence tells them apart)\n")


def _printed_word(stdout: str) -> tuple[list[str], str]:
    """The shortest distinguishing sequence equiv printed (bare names), and the file allowing it."""
    line = stdout.splitlines()[1]
    assert line.startswith("shortest distinguishing sequence: ")
    word, allowed = line.split(": ", 1)[1].split(" (allowed by ")
    return [w[3:] for w in word.split()], allowed.split(", not by ")[0]


@pytest.mark.parametrize("a, b", [(a, b) for a, b in itertools.combinations(SUPERVISORS, 2)
                                  if set(model(a).events) != set(model(b).events)],
                         ids=lambda p: p.stem)
def test_sets_with_different_events_get_a_shortest_distinguishing_word(a, b):
    """Issue 40: the word is in one language and not the other, and no shorter word over the
    events of both tells them apart."""
    result = run("equiv", a, b)
    assert result.exit_code == 1 and result.stdout.startswith("not equivalent: events in only one set: EV_")
    names, allowed = _printed_word(result.stdout)
    ma, mb = model(a), model(b)
    yes, no = (ma, mb) if allowed == str(a) else (mb, ma)
    assert allowed in (str(a), str(b))
    assert accepts(yes, names) and not accepts(no, names) and accepts(no, names[:-1])
    alphabet = sorted(set(ma.events) | set(mb.events))
    if len(alphabet) ** (len(names) - 1) <= 20000:
        for n in range(len(names)):
            for shorter in itertools.product(alphabet, repeat=n):
                assert accepts(ma, shorter) == accepts(mb, shorter)


def test_an_event_of_one_set_alone_is_the_word_when_it_can_start(tmp_path):
    """The two leaders: a start event the other set lacks is a word of one event."""
    a, b = CORPUS / "openswarm" / "hitl_leader.yaml", CORPUS / "openswarm" / "network_leader.yaml"
    names, allowed = _printed_word(run("equiv", a, b).stdout)
    ma, mb = model(a), model(b)
    assert len(names) == 1 and (names[0] in ma.events) != (names[0] in mb.events)
    assert allowed == str(a if names[0] in ma.events else b)


def variant(m, kind):
    """``m`` with its first supervisor repeated (same language, other structure), or with the
    last transition of its first state that has any removed (usually another language)."""
    if kind == "repeated":
        return replace(m, supervisors=m.supervisors + m.supervisors[:1])
    sup = m.supervisors[0]
    q = next(q for q, row in enumerate(sup.states) if row)
    states = sup.states[:q] + (sup.states[q][:-1],) + sup.states[q + 1:]
    return replace(m, supervisors=(replace(sup, states=states),) + m.supervisors[1:])


# network_worker is left out: its 10,368-state conjunction takes libFAUDES seconds to compare.
@pytest.mark.parametrize("kind", ["repeated", "dropped"])
@pytest.mark.parametrize("path", [p for p in SUPERVISORS if p.stem != "network_worker"], ids=lambda p: p.stem)
def test_equiv_agrees_with_libfaudes_on_variants_of_the_corpus(path, kind):
    m = model(path)
    other = variant(m, kind)
    ours = compare(m, other) is None
    assert ours == faudes.LanguageEquality(conjunction(m), conjunction(other))
    assert ours or kind == "dropped"


def test_equiv_agrees_with_libfaudes_on_corpus_sets_with_the_same_events():
    pairs = [(a, b) for a, b in itertools.combinations(SUPERVISORS, 2) if set(model(a).events) == set(model(b).events)]
    assert pairs
    for a, b in pairs:
        ma, mb = model(a), model(b)
        assert (compare(ma, mb) is None) == faudes.LanguageEquality(conjunction(ma), conjunction(mb))
