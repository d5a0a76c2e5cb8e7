"""The generated code of the bundled example equals the committed golden files (make golden
rewrites them after an intended change), and every runtime file a target ships is the runtime's
own file under its one-line banner."""

import pytest

from golden import HERE, expected
from swarmvm.pipeline import compile_inputs
from swarmvm.targets import TARGETS, copy_banner, generate
from checkout import EXAMPLE


@pytest.mark.parametrize("rel,data", sorted(expected().items()), ids=str)
def test_generated_file_equals_its_golden_copy(rel, data):
    golden = HERE / rel
    assert golden.is_file(), "no golden file %s: run make golden" % rel
    assert data == golden.read_bytes(), "generated %s differs from tests/golden/%s: review, then make golden" % (rel.stem, rel)


def test_no_golden_file_is_left_over():
    assert {p.relative_to(HERE) for p in HERE.rglob("*.golden")} == {r for r in expected() if r.suffix == ".golden"}


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_shipped_runtime_files_are_the_runtime_under_a_banner(target):
    files = generate(compile_inputs([str(EXAMPLE)], name="energy_worker"), target)
    for source, output in TARGETS[target].copies:
        assert files[output][0] == copy_banner(output) + source.read_bytes()
        assert files[output][0].splitlines()[0].decode().count("swarmvm gen") == 1
