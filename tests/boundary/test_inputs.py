"""Inputs, good and bad: every malformed file gets its exact one-line message and exit status 2,
with no traceback and no output written; YAML 1.1 traps keep event names as names."""

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.boundary.errors import MAX_BYTES
from swarmvm.readers.supervisor_yaml import load_supervisor
from swarmvm.compiler.pipeline import compile_inputs

INPUTS = Path(__file__).parent / "inputs"
MALFORMED = sorted((INPUTS / "malformed").glob("*.yaml"))
CORPUS = Path(__file__).parent.parent / "corpus"


def expected_message(path):
    first = path.read_text().splitlines()[0]
    assert first.startswith("# error: ")
    return first[len("# error: "):]


@pytest.mark.parametrize("path", MALFORMED, ids=lambda p: p.stem)
def test_malformed_input_gets_its_message_and_writes_nothing(path, tmp_path, monkeypatch):
    monkeypatch.chdir(path.parent)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["gen", path.name, "--target", "python", "-o", str(out)])
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: %s\n" % (path.name, expected_message(path))
    assert result.stdout == ""
    assert not out.exists()


def test_the_installed_command_reports_one_line_and_status_2():
    path = INPUTS / "malformed" / "target_out_of_range.yaml"
    proc = subprocess.run(["swarmvm", "check", str(path)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert proc.stderr.startswith("swarmvm: error: %s: sup_data[6]: supervisor 0, state 1, event EV_u" % path)


def test_a_file_over_the_size_limit_is_refused(tmp_path):
    big = tmp_path / "big.yaml"
    big.write_text("# padding\n" * (MAX_BYTES // 10 + 1))
    result = CliRunner().invoke(main, ["check", str(big)])
    assert result.exit_code == 2
    assert "over the %d-byte limit" % MAX_BYTES in result.stderr


def test_a_missing_file_is_one_line(tmp_path):
    result = CliRunner().invoke(main, ["check", str(tmp_path / "nope.yaml")])
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: cannot read file (No such file or directory)\n" % (tmp_path / "nope.yaml")


def test_yaml_1_1_words_stay_event_names():
    spec = load_supervisor(str(INPUTS / "good" / "yaml11_names.yaml"))
    assert spec.events == ["on", "off", "yes", "no", "010"]
    assert spec.controllable == {"on": True, "off": True, "yes": False, "no": False, "010": True}
    compiled = compile_inputs([str(INPUTS / "good" / "yaml11_names.yaml")])
    assert compiled.model.events == ("010", "no", "off", "on", "yes")


@pytest.mark.parametrize("name", ["flipflop_S.yaml", "public_example.yaml", "probabilistic_example.yaml"])
def test_nadzoru2_variants_load(name):
    spec = load_supervisor(str(CORPUS / "nadzoru2" / name))
    assert spec.supervisors


def test_empty_event_name_and_nonzero_initial_states():
    spec = load_supervisor(str(CORPUS / "nadzoru2" / "flipflop_S.yaml"))
    assert "" in spec.events
    assert [s.initial for s in spec.supervisors] == [1, 0]


def test_old_spelling_ev_shared_is_the_public_flag():
    spec = load_supervisor(str(CORPUS / "openswarm" / "hitl_leader.yaml"))
    assert spec.public["_requestL"] and not spec.public["pressStop"]


def test_probabilities_are_read_exactly():
    spec = load_supervisor(str(CORPUS / "nadzoru2" / "probabilistic_example.yaml"))
    probs = {t.event: t.probability for row in spec.supervisors[0].states for t in row}
    assert str(probs["b"]) == "7/10" and str(probs["a"]) == "3/10" and probs["u"] is None


def test_xml_automata_that_disagree_on_controllability_are_refused(tmp_path):
    a = (CORPUS / "automata" / "S.xml").read_text()
    flipped = a.replace('controllable="False"', 'controllable="TMP"').replace(
        'controllable="True"', 'controllable="False"').replace('controllable="TMP"', 'controllable="True"')
    (tmp_path / "S.xml").write_text(a)
    (tmp_path / "T.xml").write_text(flipped)
    result = CliRunner().invoke(main, ["pack", str(tmp_path / "S.xml"), str(tmp_path / "T.xml"), "-o", str(tmp_path / "x.svm")])
    assert result.exit_code == 2
    assert result.stderr.startswith("swarmvm: error: %s: controllable: event EV_" % (tmp_path / "T.xml"))
    assert not (tmp_path / "x.svm").exists()


def test_mixing_yaml_and_xml_is_refused():
    result = CliRunner().invoke(main, ["check", str(CORPUS / "automata" / "S.xml"), str(CORPUS / "automata" / "K.xml")])
    assert result.exit_code == 0   # check takes each file on its own
    result = CliRunner().invoke(main, ["pack", str(CORPUS / "automata" / "S.xml"),
                                       str(CORPUS / "openswarm" / "uav.yaml"), "-o", "x.svm"])
    assert result.exit_code == 2 and "not both" in result.stderr
