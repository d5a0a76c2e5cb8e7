"""Names portable across file systems (issue 37, class 9): a model name that is a Windows device
name is refused in one line by the one naming rule, and no target writes two files whose names
differ only by case (one file on Windows and macOS), whatever name it is given."""

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.naming import WINDOWS_DEVICES, file_stem
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS, _refuse_case_twins, generate

EXAMPLE = str(Path(__file__).resolve().parents[2] / "examples" / "energy_worker" / "supervisor.yaml")
COMPILED = compile_inputs([EXAMPLE])


def _any_case(word: str) -> st.SearchStrategy[str]:
    return st.lists(st.booleans(), min_size=len(word), max_size=len(word)).map(
        lambda upper: "".join(c.upper() if u else c.lower() for c, u in zip(word, upper)))


@settings(max_examples=200)
@given(st.sampled_from(sorted(WINDOWS_DEVICES)).flatmap(_any_case))
def test_a_device_name_in_any_case_is_refused_in_one_line(name):
    with pytest.raises(InputError) as caught:
        file_stem(name, "x.yaml")
    line = str(caught.value)
    assert "\n" not in line and "is a device name on Windows" in line and "--name" in line


@pytest.mark.parametrize("name", ["CONSOLE", "con_1", "COM10", "LPT", "nul2", "Auxiliary"])
def test_names_that_only_start_like_a_device_are_fine(name):
    assert file_stem(name, "x.yaml") == name


@settings(max_examples=60, deadline=None)
@given(st.from_regex(r"[A-Za-z][A-Za-z0-9_]{0,12}", fullmatch=True), st.sampled_from(sorted(TARGETS)))
def test_no_target_writes_two_names_that_differ_only_by_case(name, target):
    compiled = compile_inputs([EXAMPLE], name=name)
    try:
        files = generate(compiled, target)
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    lowered = [rel.lower() for rel in files]
    assert len(lowered) == len(set(lowered)), sorted(files)


def test_the_case_check_finds_twins():
    with pytest.raises(InputError, match="differ only by case"):
        _refuse_case_twins(COMPILED, "c", {"Model_tables.c": (b"", False), "model_tables.c": (b"", False)})
