"""`make mutation-c`'s runner (scripts/mutation_c.py): a mutant no host build compiles is told apart,
an interrupted run resumes from its results, mutants that were not judged stay out of the rate,
and the report puts the C runtime's row beside the Python modules' (mutation_report.py --also)."""

import json
import subprocess
import sys
from pathlib import Path

from checkout import ROOT

sys.path.insert(0, str(ROOT / "scripts"))
import mutation_c  # noqa: E402
import mutation_report  # noqa: E402


def record(id, outcome, digest="d1", line=3):
    return {"id": id, "digest": digest, "module": mutation_c.MODULE, "operator": "c/NumberReplacer", "line": line,
            "column": 5, "text": "x = 1;", "mutated": "x = 2;", "outcome": outcome, "seconds": 1.0}


def test_a_mutant_in_a_branch_the_preprocessor_drops_reaches_no_build(tmp_path):
    path = tmp_path / "unit.c"
    original = "int f(int a)\n{\n#if defined(__AVR__)\n    return a + 1;\n#else\n    return a - 1;\n#endif\n}\n"
    path.write_text(original)
    builds = [(), ("-D__AVR__",)]
    originals = {defines: mutation_c.preprocessed(path, defines) for defines in builds}
    path.write_text(original.replace("a + 1", "a - 1"))
    assert mutation_c.reaching_builds(path, originals) == [("-D__AVR__",)]
    assert mutation_c.reaching_builds(path, {(): originals[()]}) == []
    path.write_text(original.replace("a - 1", "a + 1"))
    assert mutation_c.reaching_builds(path, originals) == [()]


def test_a_run_resumes_from_the_last_result_of_each_mutant_of_the_same_source(tmp_path):
    results = tmp_path / "results.jsonl"
    lines = [record("c0000", "killed"), record("c0001", "survived"), record("c0002", "killed", digest="old"),
             record("c0001", "killed")]
    results.write_text("".join(json.dumps(r) + "\n" for r in lines))
    assert {k: r["outcome"] for k, r in mutation_c.done_results(results, "d1", False).items()} == \
        {"c0000": "killed", "c0001": "killed"}
    results.write_text("".join(json.dumps(r) + "\n" for r in lines[:2]))
    assert list(mutation_c.done_results(results, "d1", True)) == ["c0000"]      # survivors judged again


def test_unreached_and_stillborn_mutants_are_left_out_of_the_report(tmp_path):
    records = {"c0000": record("c0000", "killed"), "c0001": record("c0001", "unreached"),
               "c0002": record("c0002", "stillborn"), "c0003": record("c0003", "survived")}
    mutation_c.write_mutants(tmp_path, records)
    written = json.loads((tmp_path / "runtime_c__swarmvm.c.mutants.json").read_text())
    assert [m["outcome"] for m in written] == ["killed", "survived"]
    assert set(written[0]) == {"module", "operator", "line", "column", "text", "mutated", "outcome"}


def test_the_report_adds_the_c_runtimes_row_from_its_own_folder(tmp_path):
    python, c = tmp_path / "mutation", tmp_path / "mutation-c"
    python.mkdir()
    c.mkdir()
    (python / "m.mutants.json").write_text(json.dumps([{"module": "m.py", "operator": "core/NumberReplacer", "line": 2,
                                                         "column": 4, "text": "x = 1", "mutated": "x = 2",
                                                         "outcome": "killed"}]))
    mutation_c.write_mutants(c, {"c0000": record("c0000", "killed"), "c0001": record("c0001", "survived")})
    status = mutation_report.main([str(python), "--also", str(c), "--equivalents", str(tmp_path / "none.toml")])
    modules = json.loads((python / "report.json").read_text())["modules"]
    assert [(m["module"], m["killed"], m["survived"]) for m in modules] == [("m.py", 1, 0),
                                                                             ("runtime_c/swarmvm.c", 1, 1)]
    assert status == 1      # the C runtime at 50 %


def test_a_judge_that_hangs_is_killed_with_the_programs_it_started(tmp_path):
    """A mutant that makes a harness loop: at the timeout the tests and every program they
    started are killed, none left running orphaned (a zombie awaiting its reaping is dead)."""
    pid_file = tmp_path / "pid"
    command = "sh -c 'for i in 1 2 3 4; do sleep 60 & echo $! >> %s; done; wait'" % pid_file
    assert mutation_c.judge(command, tmp_path, {"PATH": "/usr/bin:/bin"}, timeout=1.0) == "timeout"
    pids = pid_file.read_text().split()
    assert len(pids) == 4
    for pid in pids:        # dead when judge returns, not some time after (SIGKILL is asynchronous)
        status = Path("/proc/%s/status" % pid)
        assert not status.exists() or "State:\tZ" in status.read_text()
    assert mutation_c.judge("true", tmp_path, {"PATH": "/usr/bin:/bin"}, timeout=5.0) == "survived"
    assert mutation_c.judge("false", tmp_path, {"PATH": "/usr/bin:/bin"}, timeout=5.0) == "killed"


def test_a_process_group_is_seen_running_until_it_is_killed():
    sleeper = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        assert mutation_c.running_in_group(sleeper.pid) == [sleeper.pid]
        mutation_c.kill_group(sleeper.pid)
        assert mutation_c.running_in_group(sleeper.pid) == []     # a zombie until reaped: dead
    finally:
        sleeper.kill()
        sleeper.wait()
