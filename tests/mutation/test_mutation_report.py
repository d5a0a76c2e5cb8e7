"""`make mutation`'s report (scripts/mutation_report.py): counts per module, equivalents set aside
by their entry in the equivalents file, the kill rate over the rest, exit status 1 under the
threshold; and the runner's reading of cosmic-ray's dump (scripts/mutation.py)."""

import json
import sqlite3
import sys

import pytest

from checkout import ROOT

sys.path.insert(0, str(ROOT / "scripts"))
import mutation  # noqa: E402
import mutation_report  # noqa: E402

LINE = "if pos >= end:"


def mutant(outcome, module="m.py", column=15, operator="core/ReplaceComparisonOperator_GtE_Gt"):
    return {"module": module, "operator": operator, "line": 12, "column": column, "text": LINE,
            "mutated": "if pos > end:", "outcome": outcome}


EQUIVALENT = """[[equivalent]]
module = "m.py"
operator = "core/ReplaceComparisonOperator_GtE_Gt"
line = "if pos >= end:"
column = 15
reason = "pos never passes end"
"""


def run_report(tmp_path, mutants, equivalents=""):
    (tmp_path / "m.mutants.json").write_text(json.dumps(mutants))
    (tmp_path / "equivalents.toml").write_text(equivalents)
    status = mutation_report.main([str(tmp_path), "--equivalents", str(tmp_path / "equivalents.toml")])
    return status, json.loads((tmp_path / "report.json").read_text())["modules"]


def test_the_rate_counts_timeouts_as_kills_and_sets_equivalents_aside(tmp_path):
    mutants = [mutant("killed", column=c) for c in range(30)] + [mutant("timeout", column=40), mutant("survived")]
    status, modules = run_report(tmp_path, mutants, EQUIVALENT)
    assert status == 0
    assert modules == [{"module": "m.py", "killed": 30, "timeout": 1, "survived": 0, "incompetent": 0,
                        "equivalent": 1, "rate": 100.0, "survivors": []}]


def test_a_module_under_97_percent_fails_the_report_and_its_survivors_are_listed(tmp_path, capsys):
    mutants = [mutant("killed", column=c) for c in range(32)] + [mutant("survived", column=99)]
    status, modules = run_report(tmp_path, mutants, EQUIVALENT)
    assert status == 1 and modules[0]["rate"] == pytest.approx(100 * 32 / 33, abs=0.01)
    assert modules[0]["survivors"] == [{"line": 12, "column": 99, "operator": "core/ReplaceComparisonOperator_GtE_Gt",
                                        "text": LINE, "mutated": "if pos > end:", "outcome": "survived"}]
    report = (tmp_path / "report.md").read_text()
    assert "| m.py | 33 | 32 | 0 | 1 | 0 | 0 | 97.0 % (under) |" in report
    assert "- line 12, column 99, core/ReplaceComparisonOperator_GtE_Gt: `if pos >= end:` -> `if pos > end:`" in report
    assert "UNDER" in capsys.readouterr().out


def test_an_equivalent_without_a_reason_is_refused(tmp_path):
    with pytest.raises(ValueError, match="without a reason"):
        run_report(tmp_path, [mutant("survived")], EQUIVALENT.replace("pos never passes end", " "))


def test_the_repository_equivalents_each_give_a_reason():
    mutation_report.load_equivalents(ROOT / "tests" / "mutation" / "equivalents.toml")


def test_the_runner_reads_cosmic_rays_dump():
    """Skipped (filtered) items are left out; a timeout is told from another kill by its output."""
    def line(operator, outcome, output="", worker="normal", row=2):
        item = {"job_id": "j", "mutations": [{"module_path": "m.py", "operator_name": operator, "occurrence": 0,
                                              "start_pos": [row, 4], "end_pos": [row, 6]}]}
        result = {"worker_outcome": worker, "output": output, "test_outcome": outcome,
                  "diff": "--- a\n+++ b\n@@ -2 +2 @@\n-    x = 1\n+    x = 2\n"}
        return json.dumps([item, result])
    dump = "\n".join([line("core/NumberReplacer", "killed"), line("core/NumberReplacer", "killed", "timeout"),
                      line("core/AddNot", None, worker="skipped"), line("core/ReplaceTrueWithFalse", "survived")])
    mutants = mutation.mutants_of("m.py", ["def f():", "    x = 1"], dump)
    assert [(m["operator"], m["outcome"]) for m in mutants] == [
        ("core/NumberReplacer", "killed"), ("core/NumberReplacer", "timeout"), ("core/ReplaceTrueWithFalse", "survived")]
    assert {(m["text"], m["mutated"], m["line"], m["column"]) for m in mutants} == {("x = 1", "x = 2", 2, 4)}


def test_the_runner_gives_cosmic_ray_absolute_paths_when_work_is_relative(tmp_path, monkeypatch):
    """cosmic-ray runs in the copy's folder: a relative --work (make's build/mutation) must reach it
    resolved, or its config and session are looked for under the copy."""
    seen = []
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(mutation, "copy_tree", lambda work: work / "tree")
    monkeypatch.setattr(mutation, "environment", lambda work, tree: {})
    monkeypatch.setattr(mutation, "run_module", lambda module, tests, kept, work, tree, env, survivors:
                        seen.append((work, tree)))
    monkeypatch.setattr(mutation.subprocess, "run", lambda *args, **kwargs: type("Run", (), {"returncode": 0}))
    assert mutation.main(["--work", "build/mutation", "--module", "generator/compiler/naming.py"]) == 0
    assert seen == [(tmp_path / "build" / "mutation", tmp_path / "build" / "mutation" / "tree")]


def test_survivors_again_forgets_only_the_surviving_and_unrunnable_results_not_marked_equivalent(tmp_path):
    """cosmic-ray exec runs the mutants without a result row: those are the ones to run again,
    but for survivors marked equivalent, which would only survive again."""
    session = tmp_path / "m.sqlite"
    with sqlite3.connect(session) as db:
        db.execute("CREATE TABLE work_results (job_id TEXT, test_outcome TEXT)")
        db.execute("CREATE TABLE mutation_specs (job_id TEXT, operator_name TEXT, start_pos_row INT, start_pos_col INT)")
        jobs = [("a", "KILLED", 2), ("b", "SURVIVED", 2), ("c", "INCOMPETENT", 2), ("d", None, 2), ("e", "SURVIVED", 1)]
        db.executemany("INSERT INTO work_results VALUES (?, ?)", [(job, outcome) for job, outcome, _ in jobs])
        db.executemany("INSERT INTO mutation_specs VALUES (?, 'core/NumberReplacer', ?, 4)",
                       [(job, row) for job, _, row in jobs])
    source = ["x = 1", "    y = 2  "]
    equivalent = {("m.py", "core/NumberReplacer", "x = 1", 4)}
    assert mutation.forget_survivors(session, "m.py", source, equivalent) == 2
    with sqlite3.connect(session) as db:
        assert db.execute("SELECT job_id FROM work_results ORDER BY job_id").fetchall() == [("a",), ("d",), ("e",)]


@pytest.mark.parametrize("recorded", [None, "0" * 64])
def test_survivors_again_is_refused_when_the_module_changed_since_its_session(tmp_path, recorded):
    """Without the digest of the module its session mutated, or with another, the session's
    mutants are not this module's: refused before any test runs."""
    tree, work = tmp_path / "tree", tmp_path / "work"
    (tree / "generator").mkdir(parents=True)
    work.mkdir()
    (tree / "generator" / "m.py").write_text("x = 1\n")
    (work / "generator__m.sqlite").write_bytes(b"")
    if recorded is not None:
        (work / "generator__m.sha256").write_text(recorded)
    with pytest.raises(SystemExit, match="^mutation: generator/m.py changed since its last session in .*, or has "
                                         "none: run it without --survivors$"):
        mutation.run_module("generator/m.py", [], [], work, tree, {}, survivors=True)
