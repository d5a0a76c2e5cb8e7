"""A target's own rule refuses the model for that target only, and ``check --target`` applies it
up front (issue 23, class 2). Message codes are pinned by known answers."""

from click.testing import CliRunner

from conformance.cases import supervisor_yaml
from swarmvm import api
from swarmvm.cli.commands import main
from swarmvm.compiler.naming import fnv1a, message_code

OTHER_TARGETS = sorted(set(api.TARGETS) - {"argos"})


def public_model(tmp_path, names, file="m.yaml"):
    """One supervisor of one state looping on controllable public events ``names``."""
    path = tmp_path / file
    path.write_text(supervisor_yaml(names, [1] * len(names), [set(names)], [[[(n, 0) for n in names]]],
                                    public=[1] * len(names)))
    return path


def test_fnv1a_and_message_codes_known_answers():
    # FNV-1a 32-bit test vectors (the offset basis, "a", "foobar"), and their 16-bit folds.
    assert (fnv1a(""), fnv1a("a"), fnv1a("foobar")) == (0x811C9DC5, 0xE40C292C, 0xBF9CF968)
    assert message_code("a") == 0xE40C ^ 0x292C == 52512
    assert (message_code("m155"), message_code("m829")) == (64330, 64330)     # a collision, used below


def test_colliding_argos_codes_refuse_the_argos_target_alone(tmp_path):
    path = public_model(tmp_path, ["m155", "m829"])
    for target in OTHER_TARGETS:
        assert api.generate_target([str(path)], target, str(tmp_path / target)).written
    result = CliRunner().invoke(main, ["gen", str(path), "-t", "argos", "-o", str(tmp_path / "argos")])
    assert result.exit_code == 2 and not (tmp_path / "argos").exists()
    assert result.stderr == ("swarmvm: error: m.yaml: events: event EV_m829: target argos: messages 'm155' and "
                             "'m829' have the same 16-bit ARGoS code 64330: rename one\n")


def test_a_double_underscore_refuses_the_argos_target_alone(tmp_path):
    """C++ reserves identifiers holding '__'; C and Python do not."""
    path = public_model(tmp_path, ["a__b"])
    for target in OTHER_TARGETS:
        assert api.generate_target([str(path)], target, str(tmp_path / target)).written
    result = CliRunner().invoke(main, ["gen", str(path), "-t", "argos", "-o", str(tmp_path / "argos")])
    assert result.exit_code == 2 and "target argos: C++ reserves identifiers with '__'" in result.stderr


def test_check_applies_one_targets_rules_up_front(tmp_path):
    path = public_model(tmp_path, ["m155", "m829"])
    runner = CliRunner()
    assert runner.invoke(main, ["check", str(path)]).exit_code == 0
    assert runner.invoke(main, ["check", str(path), "--target", "kilobot"]).exit_code == 0
    refused = runner.invoke(main, ["check", str(path), "--target", "argos"])
    assert refused.exit_code == 2 and "target argos: messages 'm155' and 'm829'" in refused.stderr
    assert list(tmp_path.iterdir()) == [path]          # nothing written


def test_check_target_names_the_model_as_gen_would(tmp_path):
    """gen refuses a model named like the runtime's own symbols; so does check --target, and
    --name gives the model another name as gen's --name does."""
    path = public_model(tmp_path, ["x"], file="svm_core.yaml")
    runner = CliRunner()
    assert runner.invoke(main, ["check", str(path)]).exit_code == 0
    refused = runner.invoke(main, ["check", str(path), "--target", "c"])
    assert refused.exit_code == 2 and "collides with the runtime's own svm_* symbols" in refused.stderr
    assert runner.invoke(main, ["check", str(path), "--target", "c", "--name", "core"]).exit_code == 0
