"""Nesting depth and number size, for every structured input (issue 37, class 6): a file nested
arbitrarily deep, or holding a number of arbitrarily many digits, loads or is refused in one
line; never a RecursionError or ValueError traceback (a budget file nested 50,000 deep was one)."""

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.footprint.budget import read_budgets
from swarmvm.footprint.delta import read_baseline


def _nested(depth: int, left: str, right: str) -> str:
    return left * depth + right * depth


# format -> (suffix, reader, file nested `depth` deep, file holding a number of `digits` digits)
FORMATS = {
    "toml": (".toml", read_budgets, lambda d: "a = %s\n" % _nested(d, "[", "]"),
             lambda n: "[kilobot]\nflash = %s\n" % ("9" * n)),
    "json": (".json", read_baseline, lambda d: _nested(d, "[", "]"), lambda n: '{"format": %s}' % ("9" * n)),
    "yaml": (".yaml", lambda p: compile_inputs([p]), lambda d: "events: %s\n" % _nested(d, "[", "]"),
             lambda n: "num_events: %s\n" % ("9" * n)),
    "nza": (".nza", lambda p: compile_inputs([p]), lambda d: "return %s\n" % _nested(d, "{", "}"),
            lambda n: "return { states = { %s } }\n" % ("9" * n)),
    "xml": (".xml", lambda p: compile_inputs([p]), lambda d: '<model type="FSA"><data>%s</data></model>'
            % _nested(d, "<s>", "</s>"), lambda n: '<model type="FSA"><data><state id="%s"/></data></model>' % ("9" * n)),
    "c": (".c", lambda p: compile_inputs([p]), lambda d: "const unsigned char ev_controllable[1] = %s;\n"
          % _nested(d, "{", "}"), lambda n: "const unsigned char ev_controllable[1] = { %s };\n" % ("9" * n)),
    "gen": (".gen", lambda p: compile_inputs([p]), lambda d: "<Generator>\n%s\n</Generator>\n" % _nested(d, "<A>", "</A>"),
            lambda n: '<Generator>\n"g"\n<States>\n%s\n</States>\n</Generator>\n' % ("9" * n)),
}


def _one_line_or_loads(tmp_path, fmt: str, text: str) -> None:
    suffix, read, _, _ = FORMATS[fmt]
    path = tmp_path / ("input" + suffix)
    path.write_text(text)
    try:
        read(str(path))
    except InputError as exc:
        assert "\n" not in str(exc) and len(str(exc)) < 6000


SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.mark.parametrize("fmt", sorted(FORMATS))
@SETTINGS
@given(depth=st.one_of(st.integers(1, 200), st.integers(200, 60_000)))
def test_any_nesting_loads_or_is_one_line(tmp_path, fmt, depth):
    _one_line_or_loads(tmp_path, fmt, FORMATS[fmt][2](depth))


@pytest.mark.parametrize("fmt", sorted(FORMATS))
@SETTINGS
@given(digits=st.one_of(st.integers(1, 80), st.integers(4000, 20_000)))
def test_any_number_size_loads_or_is_one_line(tmp_path, fmt, digits):
    _one_line_or_loads(tmp_path, fmt, FORMATS[fmt][3](digits))


@pytest.mark.parametrize("fmt", ["toml", "json"])
def test_the_bounds_are_what_the_footprint_files_say(tmp_path, fmt):
    with pytest.raises(InputError, match="nested more than 64 deep"):
        FORMATS[fmt][1](str(_write(tmp_path, fmt, FORMATS[fmt][2](65))))
    with pytest.raises(InputError, match="a number of 65 digits: at most 64"):
        FORMATS[fmt][1](str(_write(tmp_path, fmt, FORMATS[fmt][3](65))))


def _write(tmp_path, fmt, text):
    path = tmp_path / ("bound" + FORMATS[fmt][0])
    path.write_text(text)
    return path
