"""`make prove`'s comparison (tests/proof/prove.py, docs/proof.md): Eva on one configuration reports
exactly the alarms tests/proof/alarms.txt lists for it, and a planted defect (the harness built
with PROOF_PLANT: a read one byte past the image buffer) is a new alarm that fails the run; a
listed alarm Eva no longer reports fails it too; so does a call of a function Eva has neither code nor
a contract for, and a Kilobot configuration is analysed with its AVR branches. WP's part: a check
taken out of check_indices leaves one of its reads unproved.

Without frama-c the Eva tests skip, saying how to get it; under CI=true they fail instead."""

import collections
import os
import shutil

import pytest

from proof import prove

CONFIG = "kilobot"      # the quickest configuration (docs/proof.md, "How to run")


@pytest.fixture(scope="module")
def frama_c():
    if prove.frama_c() is None and os.environ.get("CI") != "true":
        pytest.skip("frama-c not found: scripts/setup.sh installs frama-c-base (apt-get install frama-c-base)")
    assert prove.frama_c() is not None, "frama-c not found, and CI=true: scripts/setup.sh installs frama-c-base"
    return prove.frama_c()


@pytest.mark.slow
def test_one_configuration_matches_the_list(frama_c, tmp_path, capsys):
    assert prove.main(["--config", CONFIG, "--work", str(tmp_path)]) == 0, capsys.readouterr().out
    # A Kilobot build is analysed as avr-gcc compiles it: its AVR branches, here avr-libc's CRC
    # step (tests/proof/avr_libc/util/crc16.h) in the image check, are the ones Eva went through.
    assert "Values at end of function _crc_ccitt_update" in (tmp_path / f"{CONFIG}.log").read_text()


@pytest.mark.slow
def test_a_function_without_code_or_contract_fails_the_run(frama_c, tmp_path, capsys):
    """Eva would analyse past it on an assumption made from its prototype alone."""
    status = prove.main(["--config", CONFIG, "--work", str(tmp_path), "-D", "PROOF_UNKNOWN_CALL=1"])
    out = capsys.readouterr().out
    assert status == 1, out
    assert "no code or contract for proof_unknown" in out, out


@pytest.mark.slow
def test_a_planted_out_of_bounds_read_fails_the_comparison(frama_c, tmp_path, capsys):
    status = prove.main(["--config", CONFIG, "--work", str(tmp_path), "-D", "PROOF_PLANT=1"])
    out = capsys.readouterr().out
    assert status == 1, out
    new = [line for line in out.splitlines() if line.startswith("prove: new alarm")]
    assert new and all("harness_core.c | main |" in line for line in new), out
    assert any("| index_bound |" in line and "< 512" in line for line in new), out


def test_a_gone_alarm_fails_and_so_does_a_new_one(tmp_path):
    alarm = (CONFIG, "swarmvm.c", "fire", "mem_access", "Unknown", r"\valid_read(st + 0)")
    listed = tmp_path / "alarms.txt"
    listed.write_text("# a comment\n" + " | ".join(alarm) + " | imprecision: an example\n")
    counts, why = prove.read_list(listed)
    assert counts == collections.Counter([alarm]) and why[alarm] == "imprecision: an example"
    assert prove.compare(collections.Counter([alarm]), counts) == []
    gone = prove.compare(collections.Counter(), counts)
    assert len(gone) == 1 and gone[0].startswith("gone")
    twice = prove.compare(collections.Counter({alarm: 2}), counts)
    assert len(twice) == 1 and twice[0].startswith("new alarm (1 x)")


def test_a_line_without_a_classification_is_refused(tmp_path):
    listed = tmp_path / "alarms.txt"
    listed.write_text("host | swarmvm.c | fire | mem_access | Unknown | \\valid_read(p) | maybe\n")
    with pytest.raises(SystemExit):
        prove.read_list(listed)


def test_every_listed_configuration_exists():
    counts, _ = prove.read_list(prove.ALARMS)
    assert {a[0] for a in counts} <= set(prove.BY_NAME)


@pytest.mark.slow
def test_the_zephyr_flash_store_is_proved(frama_c, tmp_path):
    """store-zephyr reports no alarm (docs/proof.md: the first configuration with 0), its
    harness's step loop analysed: the store's code (body_byte's CRC bytes by a test, no longer
    a shift by an amount Eva could not bound) and the CapBot's binding to Zephyr's flash map."""
    run = prove.analyse(prove.BY_NAME["store-zephyr"], tmp_path)
    assert not run.error, run.error
    assert run.alarms == []
    assert "Values at end of function area_write" in run.log.read_text()


@pytest.mark.slow
def test_wp_fails_on_a_check_that_lets_a_read_past_the_transitions(frama_c, tmp_path, monkeypatch):
    """WP proves check_indices' reads in bounds (docs/proof.md, "WP") from the test that each
    state's targets end within the header's transitions: without it, the read of a target is an
    unproved property of check_indices, where the unchanged runtime has none. A lemma WP cannot
    prove (true, so that it cannot prove anything else either: Fermat's for cubes) is an alarm,
    though the report has no row for it."""
    runtime = tmp_path / "runtime_c"
    shutil.copytree(prove.RUNTIME, runtime)
    source = (runtime / "swarmvm.c").read_text()
    bound = " || defined > total_trans - succ) {"
    lemma = "/*@ lemma one_record_fits:"
    assert source.count(bound) == 1 and source.count(lemma) == 1
    hard = ("/*@ lemma no_cube_sum: \\forall integer a, b, c;\n"
            "      0 < a && 0 < b && 0 < c ==> a * a * a + b * b * b != c * c * c; */\n")
    (runtime / "swarmvm.c").write_text(source.replace(bound, ") {").replace(lemma, hard + lemma))
    monkeypatch.setattr(prove, "RUNTIME", runtime)
    run = prove.analyse(prove.BY_NAME["host"], tmp_path / "work")
    assert not run.error, run.error
    unproved = [a for a in run.alarms if a[2] == "check_indices"]
    assert any(a[3] == "mem_access" and "target" in a[5] for a in unproved), run.alarms
    assert [a[5] for a in run.alarms if a[3] == "lemma"] == ["no_cube_sum"], run.alarms


def test_a_run_without_the_provers_fails_saying_what_is_missing(tmp_path, monkeypatch, capsys):
    """Fail closed: without Why3 (or with a Why3 that finds no CVC4 or Z3) nothing is proved."""
    real = shutil.which
    monkeypatch.setattr(prove.shutil, "which", lambda name: None if name == "why3" else real(name) or "/bin/true")
    assert prove.main(["--config", CONFIG, "--work", str(tmp_path)]) == 2
    assert "why3 not found (scripts/setup.sh installs why3 cvc4 z3)" in capsys.readouterr().err


def row(function: str, kind: str, status: str, prop: str, line: str = "10") -> dict[str, str]:
    return {"directory": "runtime_c", "file": "swarmvm.c", "line": line, "function": function,
            "property kind": kind, "status": status, "property": prop}


def test_a_property_is_an_alarm_only_when_neither_eva_nor_wp_proves_it():
    """unproved() joins Eva's and WP's reports row by row (docs/proof.md, "WP")."""
    host = prove.BY_NAME["host"]
    reached = {"validate", "fire", *prove.CHECKS.functions}
    eva = [row("fire", "mem_access", "Unknown", "a"),                 # Eva's alarm, not WP's
           row("check_indices", "mem_access", "Dead", "b"),           # taken by its contract: WP's
           row("check_indices", "mem_access", "Dead", "c"),
           row("validate", "assigns clause", "Ignored", "d"),         # Eva does not prove assigns
           row("validate", "assigns clause", "Ignored", "e"),
           row("fire", "user assertion", "Partially proven", "f"),    # Eva's partial: an alarm
           row("trailer_end", "assigns clause", "Ignored", "g")]      # never run here
    wp = [row("check_indices", "mem_access", "Unknown", "b"),
          row("check_indices", "mem_access", "Partially proven", "c"),   # on Eva's rows: proved
          row("validate", "assigns clause", "Valid", "d"),
          row("check_indices", "mem_access", "Unknown", "h", line="12")]  # only WP has it
    found = {(a[2], a[4], a[5]) for a in prove.unproved(host, eva, wp, reached)}
    assert found == {("fire", "Unknown", "a"), ("check_indices", "Unknown", "b"), ("validate", "Ignored", "e"),
                     ("fire", "Partially proven", "f"), ("check_indices", "Unknown", "h")}
    # Where the images are compiled in, Eva analyses check_indices itself: its dead code is dead.
    glue = prove.BY_NAME["kilobot-glue"]
    assert ("check_indices", "Unknown", "b") not in {(a[2], a[4], a[5]) for a in prove.unproved(glue, eva, wp, reached)}


def test_a_precondition_of_a_unit_function_is_proved_or_listed_at_each_call():
    host = prove.BY_NAME["host"]
    reached = {"validate", "fire", *prove.CHECKS.functions}
    requires = "validated: 1 ≤ w ≤ 2"
    eva = [row("check_indices", "precondition", "Unknown", requires, line="5"),
           row("validate", "precondition of check_indices", "Unknown", requires, line="40")]
    wp = [row("validate", "precondition of check_indices", "Valid", requires, line="40")]
    assert prove.unproved(host, eva, wp, reached) == []
    unproved_call = eva + [row("fire", "precondition of check_indices", "Unknown", requires, line="90")]
    assert {(a[2], a[3]) for a in prove.unproved(host, unproved_call, wp, reached)} == {
        ("fire", "precondition of check_indices")}
    # A function outside the units keeps its own precondition's row as its runs left it.
    other = [row("svm_step", "precondition", "Unknown", "p", line="5"),
             row("fire", "precondition of svm_step", "Valid", "p", line="40")]
    assert [a[2] for a in prove.unproved(host, other, [], reached | {"svm_step"})] == ["svm_step"]
