"""What the build files compile and the glue carries is decided in Python (the target records'
``values``, swarmvm.targets.values for what the C targets share): a build names only runtime files
its target ships, every C target shares one feature rule, and a Kilobot message's payload is as
long as swarmvm.targets.kilobot says."""

import pytest

from conformance.cases import supervisor_yaml
from swarmvm.targets import kilobot as kilobot_target
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS, generate

# The folder a target's build file names the runtime files from (the CapBot's is Zephyr's src/).
BUILDS = {"c": "", "kilobot": "", "capbot": "src/"}


def _model(tmp_path, names, probabilities=None):
    path = tmp_path / "m.yaml"
    path.write_text(supervisor_yaml(names, [1] * len(names), [set(names)], [[[(n, 0) for n in names]]],
                                    public=[1] * len(names), probabilities=probabilities))
    return compile_inputs([str(path)], name="m")


@pytest.mark.parametrize("target", sorted(BUILDS))
def test_a_build_compiles_only_runtime_files_its_target_ships(tmp_path, target):
    values = TARGETS[target].values(_model(tmp_path, ["go"]))
    copied = {output for _, output in TARGETS[target].copies + TARGETS[target].learned_copies}
    named = {BUILDS[target] + stem + (".h" if key == "runtime_headers" else ".c")
             for key, stems in values.items() if key.endswith(("_sources", "_headers")) for stem in stems}
    assert named and named <= copied


def test_the_kilobot_and_capbot_builds_share_one_feature_rule(tmp_path):
    """The streaming Kilobot and the CapBot both read event names: the same flags; the plain
    Kilobot leaves names out; weighted follows the model's probabilities in all three."""
    for probabilities, weighted in ((None, 0), ([[["1/2"]]], 1)):
        compiled = _model(tmp_path, ["go"], probabilities)
        kilobot, capbot = TARGETS["kilobot"].values(compiled), TARGETS["capbot"].values(compiled)
        assert kilobot["stream_features"] == capbot["features"] == [
            ("BINDINGS", 0), ("FIRST", 0), ("WEIGHTED", weighted), ("LEARNED", 0)]
        assert kilobot["features"] == [("BINDINGS", 0), ("NAMES", 0), ("FIRST", 0), ("WEIGHTED", weighted),
                                       ("LEARNED", 0)]
        makefile = generate(compiled, "kilobot")["Makefile"][0].decode()
        assert ("SVM_FEATURES = -DSVM_WITH_BINDINGS=0 -DSVM_WITH_NAMES=0 -DSVM_WITH_FIRST=0 "
                "-DSVM_WITH_WEIGHTED=%d -DSVM_WITH_LEARNED=0\n" % weighted) in makefile


def test_a_kilobot_message_carries_the_first_message_bytes_of_its_name(tmp_path, monkeypatch):
    """Cut in Python to the record's length, the one its collision rule (kilobot_messages) uses:
    a template that cut it again, to its own length, would show when that length changes."""
    compiled = _model(tmp_path, ["a_long_message_name"])
    assert '{0 /* EV_a_long_message_name */, 0, "a_long_me"},' in generate(compiled, "kilobot")["m_app.c"][0].decode()
    monkeypatch.setattr(kilobot_target, "KILOBOT_MESSAGE_BYTES", 5)
    assert '{0 /* EV_a_long_message_name */, 0, "a_lon"},' in generate(compiled, "kilobot")["m_app.c"][0].decode()
