"""Messages bounded (issue 37, class 7): user text in a message is cut to a documented length,
the cut said, whatever the input holds and whichever reader or verb refuses it."""

import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from swarmvm.boundary.errors import InputError
from swarmvm.boundary.escape import MESSAGE_LINE_LIMIT, MESSAGE_PART_LIMIT

HUGE = "x" * 500_000


@settings(max_examples=100)
@given(st.text(max_size=3000), st.text(max_size=3000), st.text(max_size=3000), st.text(max_size=3000))
def test_an_input_error_is_one_bounded_line_whatever_its_parts(file, key, where, message):
    line = str(InputError(file, key, message, where))
    assert "\n" not in line and "\r" not in line
    assert len(line) <= 4 * (MESSAGE_PART_LIMIT + 40) + 6


SYNTHESIS = Path(__file__).resolve().parents[1] / "corpus" / "synthesis" / "energy_worker"


@pytest.mark.parametrize("name, text, cut", [
    ("op.lua", "Gloc1 = %s(G1, G3)\n" % HUGE, True),                 # a synthesis script's operation
    ("arg.lua", "Gloc1 = Sync(G1, %s)\n" % HUGE, True),              # and its argument
    ("x.yaml", "num_events: %s\n" % ("9" * 500_000), False),         # a supervisor's value
    ("x.gen", "<Generator> %s" % HUGE, False),                       # a libFAUDES token
    ("x.c", "const unsigned char ev_controllable[1] = { %s };\n" % HUGE, False),
], ids=["synth_operation", "synth_argument", "yaml", "gen", "c"])
def test_a_huge_token_gives_one_bounded_line(tmp_path, name, text, cut):
    (tmp_path / name).write_text(text)
    args = (["synth", *map(str, sorted(SYNTHESIS.glob("*.nza"))), "--script", str(tmp_path / name),
             "-o", str(tmp_path / "o.yaml")] if name.endswith(".lua") else ["check", str(tmp_path / name)])
    result = subprocess.run([sys.executable, "-m", "swarmvm", *args], capture_output=True, text=True)
    assert result.returncode == 2 and result.stderr.count("\n") == 1, result.stderr[:300]
    assert len(result.stderr) <= MESSAGE_LINE_LIMIT + 100
    assert ("(499000 more characters cut)" in result.stderr) == cut, result.stderr[-200:]
