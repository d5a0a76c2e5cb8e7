"""swarmvm check --properties: each design check finds its defect in a small set built to have
it, stays quiet on the same set mended, and reports on the whole corpus."""

import pytest

from models.model_cases import CORPUS, ENERGY_WORKER, SUPERVISORS, run
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.models.properties import CHECKS, check_properties


def report(*paths):
    return check_properties(compile_inputs([str(p) for p in paths]).model)


# Each case: (check, defective set, mended set), automata as (name, transitions, controllable).
CASES = [
    ("deadlock",
     [("S", ["q0 a q1"], ("a",))],
     [("S", ["q0 a q1", "q1 b q0"], ("a",))]),
    ("no control again",
     [("S", ["q0 a q1", "q1 u q1"], ("a",))],
     [("S", ["q0 a q1", "q1 u q0"], ("a",))]),
    ("never occurs",
     [("S", ["q0 a q0", "q0 b q1", "q1 a q1"], ("a", "b")), ("T", ["t0 a t0", "t1 b t1"], ("a", "b"))],
     [("S", ["q0 a q0", "q0 b q1", "q1 a q1"], ("a", "b")), ("T", ["t0 a t0", "t0 b t0"], ("a", "b"))]),
    ("ignored input",
     [("S", ["q0 u q0", "q0 a q0"], ("a",)), ("T", ["t0 a t1", "t1 u t0"], ("a",))],
     [("S", ["q0 u q0", "q0 a q0"], ("a",)), ("T", ["t0 a t1", "t1 u t0", "t0 u t0"], ("a",))]),
    ("not confluent",
     [("S", ["q0 a q1", "q0 b q2", "q1 u q0", "q2 a q2", "q2 u q0"], ("a", "b"))],
     [("S", ["q0 a q1", "q0 b q2", "q1 b q3", "q2 a q3", "q3 u q0"], ("a", "b"))]),
]


@pytest.mark.parametrize("check,defective,mended", CASES, ids=[c[0] for c in CASES])
def test_each_check_finds_its_defect_and_only_there(write_gen, check, defective, mended):
    bad = report(*(write_gen("bad_" + n, t, c, initial=t[0].split()[0]) for n, t, c in defective))
    good = report(*(write_gen("good_" + n, t, c, initial=t[0].split()[0]) for n, t, c in mended))
    assert bad.of(check), "%s not found" % check
    assert not good.of(check), good.of(check)


def test_findings_name_the_event_the_supervisor_and_a_shortest_way_there(write_gen):
    s = write_gen("S", ["q0 u q0", "q0 a q0"], ("a",), initial="q0")
    t = write_gen("T", ["t0 a t1", "t1 u t0"], ("a",), initial="t0")
    [finding] = report(s, t).of("ignored input")
    assert finding.detail == "EV_u: supervisor 1 has no transition in state 0 (supervisor 0 has)"
    assert finding.word == ()
    confluence = write_gen("C", ["q0 x q3", "q3 a q1", "q3 b q2", "q1 u q3", "q2 a q2", "q2 u q3"], ("a", "b", "x"),
                           initial="q0")
    [finding] = report(confluence).of("not confluent")
    assert finding.detail == "EV_a or EV_b: EV_a disables EV_b" and finding.word == ("x",)


def test_a_deadlock_is_not_also_counted_as_lost_control_only(write_gen):
    result = report(write_gen("S", ["q0 a q1"], ("a",), initial="q0"))
    assert [f.word for f in result.of("deadlock")] == [("a",)]
    assert [f.word for f in result.of("no control again")] == [("a",)]


def test_the_energy_worker_is_clean_and_the_cli_prints_every_check():
    assert report(ENERGY_WORKER).findings == ()
    result = run("check", "--properties", ENERGY_WORKER)
    assert result.exit_code == 0
    assert result.stdout.splitlines()[0] == "## %s: product of 36 state(s)" % ENERGY_WORKER
    assert ["- %s: none" % c for c in CHECKS] == result.stdout.splitlines()[1:6]


def test_the_corpus_reports_what_its_models_hold():
    reports = {p.stem: report(p) for p in SUPERVISORS}
    found = {name: {c: len(r.of(c)) for c in CHECKS} for name, r in reports.items()}
    clean = {c: 0 for c in CHECKS}
    for name in ("energy_worker", "energy_worker_mc", "energy_charger", "uav", "network_leader", "hitl_leader",
                 "capbot_demo", "public_example"):
        assert found[name] == clean, name
    # network_worker: its team-switching choices are not confluent (7 pairs of controllable events).
    assert found["network_worker"] == dict(clean, **{"not confluent": 7})
    # Nadzoru 2's flip-flop example has only uncontrollable events; its probabilistic example
    # offers a or b, and a leads where b is no longer possible.
    assert found["flipflop_S"] == dict(clean, **{"no control again": 4})
    assert found["probabilistic_example"] == dict(clean, **{"not confluent": 1})


def test_source_automata_sets_are_checked_as_one_set():
    automata = sorted((CORPUS / "automata").glob("energy_worker_Sloc?.xml"))
    assert report(*automata).findings == ()
