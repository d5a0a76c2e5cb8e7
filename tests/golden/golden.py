"""Golden files: what ``swarmvm gen`` renders for the bundled example, for every target.

Every file a target renders from a template is kept under tests/golden/<target>/ with the
suffix ``.golden`` (so that it is data, not code the tools would lint or compile), and the
example's table image once as tests/golden/energy_worker.svm. Runtime files copied into a
target are not kept: they are the runtime itself (tests check the copies byte for byte).
``make golden`` rewrites them (python tests/golden/golden.py); tests/golden/test_golden.py
diffs them, so every change of generated code shows in review."""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from checkout import EXAMPLE  # noqa: E402
from swarmvm.pipeline import compile_inputs  # noqa: E402
from swarmvm.targets import TARGETS, generate  # noqa: E402

NAME = "energy_worker"


def rendered(target):
    """{relative path: bytes} of the files ``target`` renders for the example."""
    compiled = compile_inputs([str(EXAMPLE)], name=NAME)
    files = generate(compiled, target)
    names = {output.format(name=NAME) for _, output, _ in TARGETS[target].templates}
    return {rel: data for rel, (data, _keep) in files.items() if rel in names}


def expected():
    """{path under tests/golden: bytes} of every golden file."""
    files = {Path(NAME + ".svm"): compile_inputs([str(EXAMPLE)], name=NAME).image}
    for target in sorted(TARGETS):
        for rel, data in rendered(target).items():
            files[Path(target) / (rel + ".golden")] = data
    return files


def write():
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
    write()
