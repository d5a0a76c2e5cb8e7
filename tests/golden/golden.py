"""Golden files: what ``swarmvm gen`` renders, for every target, over models chosen so that every
feature of the generated code shows in a golden diff; and what ``gen`` says when it refuses.

- tests/golden/<target>/: the bundled example (examples/energy_worker), and its table image
  once as tests/golden/energy_worker.svm;
- tests/golden/corpus/<model>/<target>/: each model of MODELS (from tests/corpus), rendered as
  ``swarmvm gen <model> --target <target>`` renders it; MODELS says which feature each brings;
- tests/golden/refusals/<target>.golden: ``swarmvm gen`` of each REFUSALS case for that target,
  with the one-line error it prints (or that it generated): the refusal messages are goldens too.

A rendered file is kept with the suffix ``.golden`` (data, not code the tools would lint or
compile). Runtime files copied into a target are not kept: they are the runtime itself (tests
check the copies byte for byte), nor are the new models' images (binary; the tables files hold
them as text). ``make golden`` rewrites them all (python tests/golden/golden.py);
tests/golden/test_golden.py diffs them, so every change of generated code shows in review.
``python tests/golden/golden.py --digest`` prints one SHA-256 of everything instead of writing
(the determinism test compares two runs)."""

import contextlib
import hashlib
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from click.testing import CliRunner  # noqa: E402

from checkout import EXAMPLE, ROOT  # noqa: E402
from swarmvm.api import learned_pairs  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm.footprint.sidecar import SUFFIX  # noqa: E402
from swarmvm.targets import README, TARGETS, generate  # noqa: E402

NAME = "energy_worker"
CORPUS = ROOT / "tests" / "corpus"
MODELS_DIR = HERE / "corpus"
REFUSALS_DIR = HERE / "refusals"


@dataclass(frozen=True)
class Model:
    """A corpus model whose generated code is kept for every target that takes it."""
    path: Path                       # the input, in tests/corpus
    feature: str                     # the feature of the generated code it brings
    learned: tuple[str, ...] = ()    # --learned-check YES/NO options

    @property
    def name(self) -> str:
        """The model name gen gives it (the input's file stem), and its golden folder."""
        return self.path.stem

    def targets(self) -> list[str]:
        """The targets that generate it: with learned checks, only those that generate them
        (the others' refusal is in REFUSALS)."""
        return sorted(t for t in TARGETS if TARGETS[t].learned_templates or not self.learned)


MODELS = (
    # EV_stop, EV_respond, ... sent and EV__requestL received: the Kilobot message wiring, ARGoS
    # Heard/Send, Pi-puck broadcast/received
    Model(CORPUS / "openswarm" / "hitl_leader.yaml", "public events"),
    # the weighted policy compiled in (Kilobot, CapBot), the image's probability section
    Model(CORPUS / "nadzoru2" / "probabilistic_example.yaml", "probabilities"),
    # capableTask/notCapableTask decided by a classifier (docs/learning.md): python only
    Model(CORPUS / "openswarm" / "uav.yaml", "learned check", learned=("capableTask/notCapableTask",)),
    # 30 events (10 public), 8 supervisors, 123 states, 593 transitions
    Model(CORPUS / "openswarm" / "network_worker.yaml", "largest model"),
)


@dataclass(frozen=True)
class Refusal:
    """A ``swarmvm gen`` run that some targets refuse: the input (relative to the checkout, as a
    user types it), the options after ``--target``, and what in it some target cannot take."""
    input: str
    options: tuple[str, ...]
    why: str

    def command(self, target: str) -> list[str]:
        return ["gen", self.input, "--target", target, *self.options]


REFUSALS = (
    Refusal("tests/golden/refusals/messages_alike.xml", (),
            "two public events whose names agree on the 9 bytes of a Kilobot message"),
    Refusal("tests/golden/refusals/codes_alike.xml", (),
            "two public events with one 16-bit ARGoS range-and-bearing code"),
    Refusal("tests/golden/refusals/double_underscore.xml", (), "an event name C++ reserves ('__')"),
    Refusal("tests/corpus/openswarm/uav.yaml", ("--learned-check", "capableTask/notCapableTask"),
            "a learned check: only the targets with learned templates take it"),
    Refusal("tests/corpus/openswarm/uav.yaml", ("--learned-check", "capableTask/bid"),
            "a learned check on a controllable event"),
    Refusal("tests/corpus/nadzoru2/public_example.yaml", ("--name", "int"), "a model name C reserves"),
    Refusal("tests/corpus/nadzoru2/public_example.yaml", ("--name", "svm_robot"),
            "a model name in the runtime's own prefix"),
)


def rendered(inputs: Path, target: str, name: str | None = None, learned: tuple[str, ...] = ()) -> dict[str, bytes]:
    """{relative path: bytes} of the files ``target`` renders from templates for ``inputs``, as
    ``swarmvm gen`` renders them (the same compile and learned checks; no runtime copies), with
    the README and the footprint sidecar gen writes beside them."""
    compiled = compile_inputs([str(inputs)], name=name)
    files = generate(compiled, target, learned_checks=learned_pairs(compiled, target, learned))
    spec = TARGETS[target]
    templates = spec.templates + (spec.learned_templates if learned else ())
    names = {output.format(name=compiled.name) for _, output, _ in templates} | {README, compiled.name + SUFFIX}
    return {rel: data for rel, (data, _keep) in files.items() if rel in names}


def refusals(target: str) -> bytes:
    """What ``swarmvm gen`` prints on stderr for each REFUSALS case on ``target``: why the case
    is there, the command, then its one-line error, or ``generated`` when the target takes it."""
    from swarmvm.cli.commands import main    # here: the rendered goldens need no command line (nor the studies it loads)

    text = []
    with tempfile.TemporaryDirectory() as out, contextlib.chdir(ROOT):
        for number, case in enumerate(REFUSALS):
            command = case.command(target)
            result = CliRunner().invoke(main, command + ["-o", str(Path(out) / str(number))])
            text.append("# %s\n$ swarmvm %s -o OUT\n" % (case.why, " ".join(command)))
            text.append(result.stderr if result.exit_code == 2 else "generated (exit %d)\n" % result.exit_code)
    return "".join(text).encode("utf-8")


def expected() -> dict[Path, bytes]:
    """{path under tests/golden: bytes} of every golden file."""
    files = {Path(NAME + ".svm"): compile_inputs([str(EXAMPLE)], name=NAME).image}
    for target in sorted(TARGETS):
        for rel, data in rendered(EXAMPLE, target, name=NAME).items():
            files[Path(target) / (rel + ".golden")] = data
    for model in MODELS:
        for target in model.targets():
            for rel, data in rendered(model.path, target, learned=model.learned).items():
                files[MODELS_DIR.relative_to(HERE) / model.name / target / (rel + ".golden")] = data
    for target in sorted(TARGETS):
        files[REFUSALS_DIR.relative_to(HERE) / (target + ".golden")] = refusals(target)
    return files


def digest(files: dict[Path, bytes]) -> str:
    """One SHA-256 over every golden file's path and bytes."""
    total = hashlib.sha256()
    for rel, data in sorted(files.items()):
        total.update(b"%s\0%d\0%s" % (rel.as_posix().encode(), len(data), data))
    return total.hexdigest()


def write() -> None:
    """Rewrite every golden file, and remove the ones no target renders any more."""
    files = expected()
    for old in HERE.rglob("*.golden"):
        if old.relative_to(HERE) not in files:
            old.unlink()
    for rel, data in files.items():
        (HERE / rel).parent.mkdir(parents=True, exist_ok=True)
        (HERE / rel).write_bytes(data)
        print("wrote tests/golden/%s" % rel)


if __name__ == "__main__":
    if sys.argv[1:] == ["--digest"]:
        print(digest(expected()))
    else:
        write()
