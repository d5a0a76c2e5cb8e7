"""One naming rule (swarmvm/naming.py): callback stems, message names and codes, model names;
collisions and reserved names refused before anything is written; a kept user file whose
callbacks drifted from the model is named in a warning with a fresh skeleton beside it."""

import subprocess

import pytest

from swarmvm.errors import InputError
from swarmvm.naming import callback_stem, message_code, message_name, model_identifier

# Two local events "x" and "_x"/"received_x" clash once "_x" is spelled received_x.
CLASH = """
num_events: 3
num_supervisors: 1
events: [ EV_x,EV__x,EV_received_x ]
ev_controllable: [ 1,0,0 ]
ev_shared: [ 1,1,0 ]
sup_events: [ [ 1,1,1 ] ]
sup_init_state: [ 0 ]
sup_current_state: [ 0 ]
sup_data_pos: [ 0 ]
sup_data: [ 3,EV_x,0,0,EV__x,0,0,EV_received_x,0,0 ]
"""


def test_callback_stem_and_message_rules():
    assert callback_stem("move") == "move" and callback_stem("_start") == "received_start"
    assert message_name("_start", controllable=False) == "start" == message_name("start", controllable=True)
    assert message_name("_start", controllable=True) == "_start"
    assert message_code("start") != message_code("stop") and 0 < message_code("") <= 0xFFFF


@pytest.mark.parametrize("stem,expected", [("energy worker", "energy_worker"), ("2robots", "m_2robots"),
                                           ("ouvrière", "ouvri_re")])
def test_model_names_become_ascii_identifiers(stem, expected):
    assert model_identifier(stem, "f.yaml") == expected


@pytest.mark.parametrize("stem", ["svm", "svm_sct", "swarmvm", "class", "NULL", "int", "kilo_main", "lambda"])
def test_reserved_model_names_are_refused(stem):
    with pytest.raises(InputError, match="--name"):
        model_identifier(stem, "f.yaml")


def test_colliding_callbacks_are_refused_naming_both_events(tmp_path):
    model = tmp_path / "clash.yaml"
    model.write_text(CLASH)
    result = subprocess.run(["swarmvm", "gen", str(model), "--target", "c", "-o", str(tmp_path / "out")],
                            capture_output=True, text=True)
    assert result.returncode == 2 and not (tmp_path / "out").exists()
    assert result.stderr.count("\n") == 1 and "EV__x and EV_received_x" in result.stderr


def test_drifted_user_file_is_kept_and_named(tmp_path):
    from checkout import ROOT
    corpus = ROOT / "tests" / "corpus" / "openswarm"
    out = tmp_path / "app"
    subprocess.run(["swarmvm", "gen", str(corpus / "uav.yaml"), "--target", "python", "-o", str(out), "--name", "m"],
                   check=True, capture_output=True)
    mine = (out / "m_controller.py").read_text() + "# my code\n"
    (out / "m_controller.py").write_text(mine)
    result = subprocess.run(["swarmvm", "gen", str(corpus / "capbot_demo.yaml"), "--target", "python", "-o", str(out),
                             "--name", "m"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert (out / "m_controller.py").read_text() == mine
    warning = [line for line in result.stderr.splitlines() if "m_controller.py" in line]
    assert len(warning) == 1 and "missing" in warning[0] and "on_btnMove" in warning[0] and "stale" in warning[0]
    assert "on_bid" in warning[0] and (out / "m_controller.py.new").read_text().count("def on_btnMove") == 1
    again = subprocess.run(["swarmvm", "gen", str(corpus / "uav.yaml"), "--target", "python", "-o", str(out),
                            "--name", "m"], capture_output=True, text=True)
    assert "m_controller.py" not in again.stderr     # back in step with the model: no warning


@pytest.mark.parametrize("target,stem,name", [("c", "svm", None), ("c", "worker", "svm_sct"), ("argos", "worker", "NULL"),
                                              ("argos", "class", None), ("kilobot", "kilo_main", None)])
def test_gen_refuses_a_reserved_model_name_before_writing(target, stem, name, tmp_path):
    """A model name that would not compile on a target (a runtime's symbols, a C/C++ keyword or
    macro) is one line at `gen`, nothing written: never generated code that does not build."""
    from checkout import EXAMPLE
    model = tmp_path / (stem + ".yaml")
    model.write_text(EXAMPLE.read_text())
    result = subprocess.run(["swarmvm", "gen", str(model), "--target", target, "-o", str(tmp_path / "out"),
                             *(["--name", name] if name else [])], capture_output=True, text=True)
    assert result.returncode == 2 and not (tmp_path / "out").exists()
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("swarmvm: error: %s: --name: model name %r"
                                                                       % (model, name or stem))
