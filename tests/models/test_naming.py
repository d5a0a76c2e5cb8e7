"""One naming rule (generator/compiler/naming.py): callback stems, message names and codes, model names;
collisions and reserved names refused before anything is written; a kept user file whose
callbacks drifted from the model is named in a warning with a fresh skeleton beside it."""

import subprocess

import pytest

from conformance.cases import supervisor_yaml
from swarmvm.boundary.errors import InputError
from swarmvm.compiler.naming import MAX_MODEL_NAME, callback_stem, message_code, message_name, model_identifier
from swarmvm.targets import TARGETS

# Two local events "x" and "_x"/"received_x" clash once "_x" is spelled received_x.
def clash_yaml(events=("x", "_x", "received_x"), public=(1, 1, 0)):
    """One supervisor, one state, a self-loop on each event; the first controllable."""
    return supervisor_yaml(list(events), [1, 0, 0], [set(events)], [[[(e, 0) for e in events]]], public=list(public))


def test_callback_stem_and_message_rules():
    assert callback_stem("move") == "move" and callback_stem("_start") == "received_start"
    assert message_name("_start", controllable=False) == "start" == message_name("start", controllable=True)
    assert message_name("_start", controllable=True) == "_start"
    assert message_code("start") != message_code("stop") and 0 < message_code("") <= 0xFFFF


@pytest.mark.parametrize("stem,expected", [("energy worker", "energy_worker"), ("2robots", "m_2robots"),
                                           ("ouvrière", "ouvri_re"), ("sct", "sct"), ("n" * MAX_MODEL_NAME,) * 2])
def test_model_names_become_ascii_identifiers(stem, expected):
    assert model_identifier(stem, "f.yaml") == expected


# SCT: the C compatibility layer's SCT_* functions (SCT_vm clashed with a Kilobot model's <model>_vm);
# found by the property tests (tests/properties), as was the length limit.
@pytest.mark.parametrize("stem", ["svm", "svm_sct", "swarmvm", "class", "NULL", "int", "kilo_main", "lambda", "SCT",
                                  "SCT_model", "n" * (MAX_MODEL_NAME + 1)])
def test_reserved_model_names_are_refused(stem):
    with pytest.raises(InputError, match="--name"):
        model_identifier(stem, "f.yaml")


def test_the_longest_model_name_gives_file_names_that_fit():
    """MAX_MODEL_NAME is what the longest generated file name (a kept file's fresh skeleton,
    <file>.new) leaves of 255 bytes."""
    name = model_identifier("n" * MAX_MODEL_NAME, "f.yaml")
    longest = max(len(out.format(name=name).rsplit("/", 1)[-1]) + (len(".new") if keep else 0)
                  for spec in TARGETS.values() for _, out, keep in spec.templates + spec.learned_templates)
    assert longest == 255


def test_a_rule_of_one_target_refuses_for_that_target_only_and_names_it(tmp_path):
    """Two public events whose messages share their first 9 characters are one Kilobot message:
    gen --target kilobot refuses them in one line naming the target; gen --target c accepts."""
    model = tmp_path / "m.yaml"
    model.write_text(clash_yaml(("x", "longname_a", "longname_b"), public=(1, 1, 1)))
    refused = subprocess.run(["swarmvm", "gen", str(model), "--target", "kilobot", "-o", str(tmp_path / "k")],
                             capture_output=True, text=True)
    assert refused.returncode == 2 and not (tmp_path / "k").exists()
    assert refused.stderr.count("\n") == 1 and ": target kilobot: " in refused.stderr, refused.stderr
    subprocess.run(["swarmvm", "gen", str(model), "--target", "c", "-o", str(tmp_path / "c")], check=True,
                   capture_output=True)


def test_colliding_callbacks_are_refused_naming_both_events(tmp_path):
    model = tmp_path / "clash.yaml"
    model.write_text(clash_yaml())
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


@pytest.mark.parametrize("stem", ["new", "svm", "kilo_main"])
def test_verbs_that_generate_no_code_take_any_model_name(stem, tmp_path):
    """Only gen names code after the model: check, pack, script, equiv, export and synth (which
    names its files after --output and has no --name) take a supervisor or an output called
    new.yaml or svm.yaml like any other, and gen refuses the name, saying to give another."""
    from checkout import EXAMPLE, ROOT
    model = tmp_path / (stem + ".yaml")
    model.write_text(EXAMPLE.read_text())
    synthesis = ROOT / "tests" / "corpus" / "synthesis" / "energy_worker"
    for verb in (["check", model], ["pack", model, "-o", tmp_path / "m.svm"], ["script", model, "--steps", "3"],
                 ["equiv", model, EXAMPLE], ["export", model, "-f", "dot", "-o", tmp_path / "dot"],
                 ["synth", "--script", synthesis / "script.txt", *sorted(synthesis.glob("[GE]?.xml")),
                  "-o", tmp_path / "synth" / model.name]):
        result = subprocess.run(["swarmvm", *map(str, verb)], capture_output=True, text=True)
        assert result.returncode == 0 and result.stderr == "", (verb, result.stderr)
    assert (tmp_path / "m.svm").read_bytes()[:4] == b"SVMI"
    assert (tmp_path / "dot" / (stem + "_product.dot")).is_file() and (tmp_path / "synth" / model.name).is_file()
    refused = subprocess.run(["swarmvm", "gen", str(model), "--target", "c", "-o", str(tmp_path / "out")],
                             capture_output=True, text=True)
    assert refused.returncode == 2 and "give another with --name" in refused.stderr
