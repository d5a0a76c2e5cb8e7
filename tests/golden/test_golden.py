"""The generated code of the bundled example and of the feature models (golden.MODELS) equals the
committed golden files for every target, and so do gen's refusal messages (make golden rewrites
them after an intended change); the goldens really show each feature (a golden set that lost
one fails here, not only in review); rendering is deterministic; and every runtime file a
target ships is the runtime's own file under its one-line banner."""

import difflib
import glob
import os
import subprocess
import sys

import pytest

from checkout import EXAMPLE, ROOT
from golden import HERE, MODELS, MODELS_DIR, REFUSALS, REFUSALS_DIR, digest, expected
from swarmvm.compiler.naming import event_names
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS, copy_banner, generate

EXPECTED = expected()


def readable_diff(golden, data, rel):
    """A unified diff of the golden file and what is generated now (the first 60 lines)."""
    lines = list(difflib.unified_diff(golden.decode("utf-8", "replace").splitlines(),
                                      data.decode("utf-8", "replace").splitlines(),
                                      "tests/golden/%s" % rel, "generated now", lineterm=""))
    shown = lines[:60] + (["... %d more diff lines" % (len(lines) - 60)] if len(lines) > 60 else [])
    return "\n".join(shown)


@pytest.mark.parametrize("rel", sorted(EXPECTED), ids=str)
def test_generated_file_equals_its_golden_copy(rel):
    data, golden = EXPECTED[rel], HERE / rel
    assert golden.is_file(), "no golden file %s: run make golden" % rel
    old = golden.read_bytes()
    assert data == old, "generated %s differs from tests/golden/%s (review, then make golden):\n%s" % (
        rel.name, rel, readable_diff(old, data, rel))


def test_no_golden_file_is_left_over():
    assert {p.relative_to(HERE) for p in HERE.rglob("*.golden")} == {r for r in EXPECTED if r.suffix == ".golden"}


@pytest.mark.slow
def test_rendering_is_deterministic_across_processes():
    """Two fresh interpreters with different hash seeds (set and dict orders) render the same bytes
    as this one."""
    digests = set()
    for seed in ("1", "2"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        run = subprocess.run([sys.executable, str(HERE / "golden.py"), "--digest"], env=env,
                             capture_output=True, text=True, check=True)
        digests.add(run.stdout.strip())
    assert digests == {digest(EXPECTED)}


def golden_text(model, target, rel):
    return (MODELS_DIR / model.name / target / (rel.format(name=model.name) + ".golden")).read_text("utf-8")


def model_bringing(feature):
    [model] = [m for m in MODELS if m.feature == feature]
    return model


def test_every_feature_model_has_goldens_for_every_target_that_takes_it():
    for model in MODELS:
        assert model.targets() == sorted(TARGETS if not model.learned else
                                         [t for t in TARGETS if TARGETS[t].learned_templates])
        for target in model.targets():
            assert list((MODELS_DIR / model.name / target).rglob("*.golden")), (model.name, target)


@pytest.mark.parametrize("feature", ["public events", "largest model"])
def test_public_events_show_as_message_wiring_in_the_goldens(feature):
    """Sent and received public events: the Kilobot wire table, ARGoS Heard/Send with the 16-bit
    codes, Pi-puck received/broadcast by message name."""
    model = model_bringing(feature)
    public = [e for e in event_names(compile_inputs([str(model.path)]).model) if e.public]
    assert {e.controllable for e in public} == {True, False}, "the model must send and receive messages"
    argos = golden_text(model, "argos", "{name}_base.h")
    kilobot = golden_text(model, "kilobot", "{name}_app.c")
    pipuck = golden_text(model, "pipuck", "{name}_controller.py")
    for e in public:
        assert '{%d /* %s */, %d, "%s"}' % (e.index, e.const, not e.controllable, e.message[:9]) in kilobot
        assert ("%s(%du" % ("Send" if e.controllable else "Heard", e.code)) in argos
        assert 'self.robot.%s("%s")' % ("broadcast" if e.controllable else "received", e.message) in pipuck


def test_probabilities_compile_the_weighted_policy_in():
    model = model_bringing("probabilities")
    assert compile_inputs([str(model.path)]).tables.probs is not None
    for target, rel in (("kilobot", "Makefile"), ("capbot", "CMakeLists.txt")):
        assert "-DSVM_WITH_WEIGHTED=1" in golden_text(model, target, rel)
        assert "-DSVM_WITH_WEIGHTED=1" not in (HERE / target / (rel + ".golden")).read_text("utf-8")


def test_the_learned_check_is_generated():
    model = model_bringing("learned check")
    yes, no = model.learned[0].split("/")
    learned = golden_text(model, "python", "{name}_learned.py")
    assert '("%s", "%s"),' % (yes, no) in learned
    assert "def check_%s(self, data):" % yes in learned and "def check_%s(self, data):" % no in learned
    assert "class Controller(learned.LearnedChecks):" in golden_text(model, "python", "{name}_controller.py")


def test_the_largest_corpus_model_is_a_golden():
    corpus = [compile_inputs([path]) for path in glob.glob(str(ROOT / "tests" / "corpus" / "*" / "*.yaml"))]
    largest = max(corpus, key=lambda c: (c.tables.num_states, c.tables.num_transitions))
    assert largest.model.source == model_bringing("largest model").path.name


def refusal_outcomes(target):
    """{REFUSALS case: the error line, or None when gen generated}, read from the golden."""
    text = (REFUSALS_DIR / (target + ".golden")).read_text("utf-8").splitlines()
    assert len(text) == 3 * len(REFUSALS), "each case: why, its command line, then one line"
    outcomes = {}
    for case, (why, command, outcome) in zip(REFUSALS, zip(text[::3], text[1::3], text[2::3])):
        assert (why, command) == ("# " + case.why, "$ swarmvm %s -o OUT" % " ".join(case.command(target)))
        assert outcome.startswith("swarmvm: error: ") or outcome == "generated (exit 0)", outcome
        outcomes[case] = outcome if outcome.startswith("swarmvm: error: ") else None
    return outcomes


def test_each_target_refuses_what_it_cannot_take_and_only_that():
    outcomes = {target: refusal_outcomes(target) for target in TARGETS}
    refused_by = {case.input.rsplit("/", 1)[-1] + " " + " ".join(case.options):
                  {t for t in TARGETS if outcomes[t][case]} for case in REFUSALS}
    learning = {t for t in TARGETS if TARGETS[t].learned_templates}
    assert refused_by == {
        "messages_alike.xml ": {"kilobot"},
        "codes_alike.xml ": {"argos"},
        "double_underscore.xml ": {"argos"},
        "uav.yaml --learned-check capableTask/notCapableTask": set(TARGETS) - learning,
        "uav.yaml --learned-check capableTask/bid": set(TARGETS),
        "public_example.yaml --name int": set(TARGETS),
        "public_example.yaml --name svm_robot": set(TARGETS)}
    assert "one Kilobot message 'reportPos'" in outcomes["kilobot"][REFUSALS[0]]
    assert "same 16-bit ARGoS code" in outcomes["argos"][REFUSALS[1]]
    assert "C++ reserves identifiers with '__'" in outcomes["argos"][REFUSALS[2]]


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_shipped_runtime_files_are_the_runtime_under_a_banner(target):
    files = generate(compile_inputs([str(EXAMPLE)], name="energy_worker"), target)
    for source, output in TARGETS[target].copies:
        assert files[output][0] == copy_banner(output) + source.read_bytes()
        assert files[output][0].splitlines()[0].decode().count("swarmvm gen") == 1
