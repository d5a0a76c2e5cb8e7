"""User text through every target (issue 23): whatever ``gen`` accepts compiles, and nothing
planted in a file name or a model name runs.

Hypothesis draws file names and ``--name`` values from arbitrary Unicode mixed with fragments
that end a comment, a string or a line in one of the languages swarmvm writes (C, C++, Python,
Make, CMake), each fragment carrying a canary command. For each target, ``gen`` either refuses
in one line or writes code that builds with the target's real tools (the builds of
test_random_sets.py); the canary must appear in no command ``make -n`` would run, in no output of
the generated CMake files run by cmake itself, and as no file in the output folder."""

import re
import subprocess
import tempfile
from pathlib import Path

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from properties.test_random_sets import BUILDS, run, tools  # noqa: F401  (tools: a fixture)
from swarmvm import api

CANARY = "SWARMVM_CANARY"
# The canary as a word of its own: a command's argument, not part of a file or identifier name
# (gen makes a model name of the file name, so x_touch_SWARMVM_CANARY_app.c is expected).
PLANTED = re.compile(r"(?<![A-Za-z0-9_])%s(?![A-Za-z0-9_])" % CANARY)
CORPUS = Path(__file__).resolve().parents[1] / "corpus"
# A model with public events (messages on every target) and one with probabilities.
MODELS = (CORPUS / "nadzoru2" / "public_example.yaml", CORPUS / "nadzoru2" / "probabilistic_example.yaml")
FRAGMENTS = (
    "\nall:\n\ttouch %s\n#" % CANARY,                         # a Make rule
    "\n$(shell touch %s)\n" % CANARY,                          # Make's shell function
    '")\nmessage(%s)\nfile(WRITE %s x)\n#' % (CANARY, CANARY),  # CMake commands
    '"""\nopen("%s", "w")\n"""' % CANARY,                    # the end of a Python docstring
    "*/ int %s; /*" % CANARY, "\\", "??/", "--", "\r", "\x1b[2J", "\u202e", "`touch %s`" % CANARY, "$(", "#",
)
# Neutralises the commands the generated CMakeLists.txt files call (they need ARGoS or Zephyr), so
# that cmake -P runs each one: any command injected into it would run and show the canary.
CMAKE_HARNESS = """foreach(command IN ITEMS cmake_minimum_required project find_package target_sources
    target_compile_options target_compile_definitions target_include_directories include
    swarmvm_argos_controller)
  cmake_language(EVAL CODE "function(${command})\\nendfunction()")
endforeach()
file(READ "${CMAKE_CURRENT_LIST_DIR}/CMakeLists.txt" code)
cmake_language(EVAL CODE "${code}")
"""


def hostile_text():
    return st.lists(st.one_of(st.text(max_size=6), st.sampled_from(FRAGMENTS)), min_size=1, max_size=5).map("".join)


def file_name(text):
    """``text`` made a file name: no '/' or NUL, at most 200 bytes before ``.yaml``."""
    name = text.replace("/", "_").replace("\0", "_").encode("utf-8")[:200].decode("utf-8", "ignore")
    return (name if name.strip(".") else "m") + ".yaml"


def planted(out: Path, target: str, kilolib: Path) -> list[str]:
    """Where the canary ran or would run: in ``make -n``, in cmake's own reading, as a file."""
    found = [str(p) for p in out.rglob(CANARY)]
    if (out / "Makefile").is_file():
        dry = subprocess.run(["make", "-n", "KILOLIB=%s" % kilolib], cwd=out, capture_output=True, text=True)
        found += ["make -n: " + line for line in (dry.stdout + dry.stderr).splitlines() if PLANTED.search(line)]
    for cmake_lists in out.rglob("CMakeLists.txt"):
        harness = cmake_lists.parent / "harness.cmake"
        harness.write_text(CMAKE_HARNESS)
        result = subprocess.run(["cmake", "-P", str(harness)], cwd=cmake_lists.parent, capture_output=True, text=True)
        harness.unlink()
        found += ["cmake: " + line for line in (result.stdout + result.stderr).splitlines() if PLANTED.search(line)]
        found += [str(p) for p in cmake_lists.parent.rglob(CANARY)]
    return found


@pytest.mark.slow
@settings(max_examples=6)
@given(hostile_text(), st.one_of(st.none(), hostile_text()), st.sampled_from(MODELS))
# Seen on main at 7f1712f: a file name that is a Make rule (command execution at `make`), one that
# ends the Python module's docstring, and the model name cci, whose ARGoS include guard
# CCI_CONTROLLER_H is ARGoS's own (ci_controller.h): the controller did not compile.
@example("x\nall:\n\ttouch %s\n#" % CANARY, None, MODELS[0])
@example('a"""b', None, MODELS[0])
@example("m", "cci", MODELS[0])
def test_what_gen_accepts_builds_and_runs_nothing_planted(tools, text, name, model):  # noqa: F811
    with tempfile.TemporaryDirectory() as folder:
        source = Path(folder) / file_name(text)
        source.write_bytes(model.read_bytes())
        problems = {}
        for target in sorted(BUILDS):
            out = Path(folder) / ("out-" + target)
            try:
                generated = api.generate_target([str(source)], target, str(out), name=name)
            except api.InputError as error:
                assert "\n" not in str(error) and "\x1b" not in str(error), error
                continue
            problems[target] = planted(out, target, tools.kilolib) or BUILDS[target](out, generated.compiled, tools)
        assert {t: p for t, p in problems.items() if p} == {}


def test_the_canary_check_finds_a_planted_make_rule_and_cmake_command(tmp_path, tools):  # noqa: F811
    """The check above can fail: a Makefile and a CMakeLists.txt written with the canary raw."""
    (tmp_path / "Makefile").write_text("# x\nall:\n\ttouch %s\n" % CANARY)
    (tmp_path / "CMakeLists.txt").write_text('# x\nmessage("%s")\n' % CANARY)
    found = planted(tmp_path, "c", tools.kilolib)
    assert any(f.startswith("make -n") for f in found) and any(f.startswith("cmake") for f in found), found
