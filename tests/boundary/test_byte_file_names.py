"""File names as bytes (issue 37, point 7): on POSIX a file name is any bytes but "/" and NUL, not
always UTF-8. Python hands such a name to swarmvm as text with surrogate escapes (os.fsdecode),
exactly as sys.argv holds it. Every verb that reads or writes by that name answers with status 0
or 2, prints only printable text (the name escaped, never raw bytes or a traceback), and
whatever it writes it writes under the name asked for."""

import os
import shutil
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from swarmvm.cli.commands import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "energy_worker" / "supervisor.yaml"
NAME_BYTE = st.integers(1, 255).filter(lambda b: b != ord("/"))
# Bytes that appear in no UTF-8 text (0xC0, 0xC1, 0xF5-0xFF): a name with one is never UTF-8, so
# the surrogate path is always taken.
NEVER_UTF8 = [0xC0, 0xC1, *range(0xF5, 0x100)]
BYTE_NAME = st.builds(lambda head, odd, tail: bytes(head) + bytes([odd]) + bytes(tail),
                      st.lists(NAME_BYTE, max_size=6), st.sampled_from(NEVER_UTF8), st.lists(NAME_BYTE, max_size=6))
SETTINGS = settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


def printable(text: str) -> bool:
    return all(c == "\n" or c.isprintable() for c in text) and "Traceback" not in text


def run(*args: str):
    return CliRunner().invoke(main, list(args))


@SETTINGS
@given(name=BYTE_NAME)
def test_check_and_pack_read_a_file_named_by_any_bytes(name, tmp_path_factory):
    folder = tmp_path_factory.mktemp("bytes")
    source = os.path.join(os.fsencode(folder), name + b".yaml")
    shutil.copyfile(EXAMPLE, source)
    path = os.fsdecode(source)
    checked = run("check", path)
    assert checked.exit_code == 0 and printable(checked.stdout + checked.stderr), (name, checked.output)
    image = os.fsdecode(os.path.join(os.fsencode(folder), name + b".svm"))
    packed = run("pack", path, "-o", image)
    assert packed.exit_code == 0 and printable(packed.stdout + packed.stderr), (name, packed.output)
    assert os.path.isfile(os.fsencode(image)), name
    assert run("check", image).exit_code == 0


@SETTINGS
@given(name=BYTE_NAME)
def test_gen_names_a_model_of_any_bytes_or_refuses_it_in_one_line(name, tmp_path_factory):
    folder = tmp_path_factory.mktemp("bytes")
    source = os.path.join(os.fsencode(folder), name + b".yaml")
    shutil.copyfile(EXAMPLE, source)
    out = os.path.join(os.fsencode(folder), b"out")
    result = run("gen", os.fsdecode(source), "--target", "c", "-o", os.fsdecode(out))
    assert result.exit_code in (0, 2) and printable(result.stdout + result.stderr), (name, result.output)
    if result.exit_code == 2:
        assert len(result.stderr.splitlines()) == 1 and not os.path.exists(out), (name, result.stderr)
    else:
        assert os.listdir(out), name


def test_the_names_drawn_are_not_utf8():
    """The strategy draws what it is for: names no UTF-8 decoder accepts."""
    @settings(max_examples=50, deadline=None)
    @given(name=BYTE_NAME)
    def undecodable(name):
        try:
            name.decode("utf-8")
        except UnicodeDecodeError:
            return
        raise AssertionError("%r is UTF-8" % name)
    undecodable()
