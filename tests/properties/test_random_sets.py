"""Property tests over random local-modular supervisor sets (strategies.py; docs/conformance.md).

For sets, names, event scripts and seeds hypothesis draws: (a) the Python reference VM, the C VM
built on the host and the C++ VM print the same trace; (b) every trace is a run every local
supervisor, read straight from the file, accepts: no event takes an undefined transition unless
the trace counts it as a violation; (c) ``swarmvm gen`` either writes code that compiles on every
target, or refuses the set with one line that names the target. The examples are few and short
in CI (the ``ci`` profile, tests/conftest.py); ``HYPOTHESIS_PROFILE=long`` runs many more."""

import os
import subprocess
import sys
import tempfile
from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import event, example, given, settings
from hypothesis import strategies as st

from targets.argos.argos_project import NO_ARGOS, find_argos
from conformance import c_harness, qemu_harness
from conformance._c_compare import mismatches
from conformance.cases import Batch, Run, reference, supervisor_yaml
from conformance.cpp_harness import FLAGS, runs_text
from conformance.file_oracle import FileOracle
from targets.kilobot.needs import kilolib_or_skip
from properties.strategies import MODEL_NAMES, RUN_OPTIONS, SupervisorSet, scripts, supervisor_sets
from swarmvm import api
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_CPP
from swarmvm.readers.event_script import format_script


def write_set(folder, supervisor_set):
    path = Path(folder) / "model.yaml"
    path.write_text(supervisor_set.yaml())
    return path


def as_indices(script, events):
    """A script of bare names as rows of canonical event indices."""
    return tuple(frozenset(events.index(e) for e in row) for row in script)


@pytest.fixture(scope="module")
def cpp_harness(tmp_path_factory):
    """The C++ conformance harness, built once; each example's image is loaded from its file."""
    exe = tmp_path_factory.mktemp("cpp_harness") / "harness"
    subprocess.run(["g++", *FLAGS, "-I", str(RUNTIME_CPP), "-o", str(exe),
                    str(RUNTIME_CPP / "conformance_harness.cpp")], check=True)
    return exe


@st.composite
def set_with_runs(draw):
    """A supervisor set, two scripts of one length, a few runs over them, and whether the C VM is
    built with the set's exact limits (its mask width's unrolled step) or the default ones (the
    generic step)."""
    supervisor_set = draw(supervisor_sets())
    steps = draw(st.integers(1, 12))
    first, second = draw(scripts(supervisor_set, steps, steps)), draw(scripts(supervisor_set, steps, steps))
    runs = draw(st.lists(RUN_OPTIONS.map(lambda o: Run(o["inputs"], o["control"], o["policy"], o["seed"], 0)),
                         min_size=1, max_size=4))
    runs = [Run(r.inputs, r.control, r.policy, r.seed, k % 2) for k, r in enumerate(runs)]
    return supervisor_set, (first, second), tuple(runs), draw(st.booleans())


@pytest.mark.slow
@settings(max_examples=settings.default.max_examples * 3)
@given(set_with_runs())
def test_python_c_and_cpp_print_the_same_trace(cpp_harness, drawn):
    supervisor_set, named_scripts, runs, exact_limits = drawn
    with tempfile.TemporaryDirectory() as folder:
        compiled = compile_inputs([str(write_set(folder, supervisor_set))])
        events = list(compiled.model.events)
        batch = Batch("random", folder, compiled.image, tuple(as_indices(s, events) for s in named_scripts), runs)
        exe = c_harness.build_host(batch, Path(folder) / "c", exact_limits=exact_limits)
        traces, info = c_harness.parse(c_harness.run_host(exe))
        assert mismatches(batch, traces, info, passes=(0, 1)) == []
        image, runs_file = Path(folder) / "model.svm", Path(folder) / "model.runs"
        image.write_bytes(batch.image)
        runs_file.write_text(runs_text(batch))
        out = subprocess.run([str(cpp_harness), "--image", str(image), str(runs_file)], capture_output=True, text=True,
                             check=True).stdout
        assert out == "".join("\n".join(reference(batch, run)) + "\nend\n" for run in batch.runs)


def replay_on_the_file(path, lines):
    """Replays a trace's fired events on each local supervisor of the file (conformance.file_oracle):
    the steps where an event took an undefined transition without a violation counted, or a
    controllable event fired that a supervisor cannot take, or the states printed are no
    renaming of the file's (empty = the trace is accepted)."""
    oracle = FileOracle(str(path))
    states, violations, renaming, problems = list(oracle.initial), 0, [dict() for _ in oracle.initial], []
    for line in lines:
        step, fired, printed, counter = line.split()
        missed = 0
        for name in [] if fired == "-" else fired.split(","):
            taken = oracle.apply(states, name)
            if taken and name in oracle.controllable:
                problems.append("step %s: controllable %s fired where %d supervisor(s) disable it"
                                % (step, name, taken))
            missed += taken
        violations += missed
        if int(counter) != violations:
            problems.append("step %s: %d undefined transitions in all, the trace counts %s violations"
                            % (step, violations, counter))
        for s, (mine, theirs) in enumerate(zip(states, map(int, printed.split(",")))):
            if renaming[s].setdefault(mine, theirs) != theirs or len(set(renaming[s].values())) != len(renaming[s]):
                problems.append("step %s: supervisor %d is in file state %d, printed %d" % (step, s, mine, theirs))
    return problems


@st.composite
def set_script_and_options(draw):
    """A supervisor set, its script (drawn here, or `swarmvm script`'s: steps, seed, density) and options."""
    supervisor_set = draw(supervisor_sets())
    script = draw(scripts(supervisor_set, max_steps=40) |
                  st.tuples(st.integers(1, 40), st.integers(0, 2 ** 32 - 1), st.floats(0, 1)))
    return supervisor_set, script, draw(RUN_OPTIONS)


@settings(max_examples=settings.default.max_examples * 10)
@given(set_script_and_options())
def test_every_trace_is_accepted_by_every_local_supervisor(drawn):
    supervisor_set, script, options = drawn
    with tempfile.TemporaryDirectory() as folder:
        path = write_set(folder, supervisor_set)
        script_path = Path(folder) / "events.txt"
        if isinstance(script, tuple):
            text, steps = api.make_script([str(path)], *script), script[0]
        else:
            events = compile_inputs([str(path)]).model.events
            text, steps = format_script(as_indices(script, list(events)), events), len(script)
        script_path.write_text(text)
        lines = list(api.trace([str(path)], str(script_path), seed=options["seed"], input_mode=options["inputs"],
                               control=options["control"], policy=options["policy"]))
        assert len(lines) == steps
        assert replay_on_the_file(path, lines) == []


# (c) Generated code compiles on every target. Each target's check, with the flags its own tests
# use: the Python ones import the application and step it, the C one builds with its Makefile and
# runs, the Kilobot one builds with its Makefile against the real kilolib (flash-only and
# streaming), the CapBot sources compile for the Cortex-M4F against firmware/capbot's Zephyr
# declarations and its qemu/ Makefile builds the bare-metal image (validating and minimal), the
# ARGoS controller compiles (-fsyntax-only) against the real ARGoS headers.
STRICT_C = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
ARM = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16"]
LUA_INCLUDE = Path("/usr/include/lua5.3")     # an ARGoS built with Lua includes <lua.h> from its headers


def run(command, cwd):
    """Runs a build or program; its output on failure, else None."""
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=300)
    return None if result.returncode == 0 else "%s: exit %d\n%s%s" % (
        " ".join(map(str, command))[:200], result.returncode, result.stdout[-3000:], result.stderr[-3000:])


def build_python(out, compiled, _tools):
    step = "import %s_app as app\nvm = app.make_vm()\nfor _ in range(5): vm.step()" % compiled.name
    return run([sys.executable, "-c", step], out)


def build_pipuck(out, compiled, _tools):
    return run([sys.executable, "-m", compiled.name + "_app", "--sim", "--steps", "5", "--period", "0"], out)


def build_c(out, compiled, _tools):
    name = compiled.name
    return run(["make", "-s", "CFLAGS=%s -O0" % " ".join(STRICT_C), name], out) or run(["./" + name, "5"], out)


def build_kilobot(out, compiled, tools):
    return next(filter(None, (run(["make", "-s", "-B", "KILOLIB=%s" % tools.kilolib, "CPPFLAGS=-Wextra -Werror -pedantic",
                                   *variant, compiled.name + ".elf"], out) for variant in ([], ["STREAM=1"]))), None)


def build_capbot(out, compiled, _tools):
    limits = c_harness.limits(compiled)
    return next(filter(None, (run(["arm-none-eabi-gcc", *STRICT_C, *ARM, *limits, "-I", str(qemu_harness.CAPBOT),
                                   "-I", "src", "-c", str(source), "-o", source.stem + ".o"], out)
                              for source in sorted((out / "src").glob("*.c")))), None) or next(filter(None, (
        run(["make", "-s", "-C", "qemu", *profile], out) for profile in ([], ["MINIMAL=1"]))), None)   # its qemu/ build


def build_argos(out, compiled, tools):
    lua = ["-isystem", str(LUA_INCLUDE)] if LUA_INCLUDE.is_dir() else []
    return run(["g++", "-std=c++17", "-Wall", "-Wextra", "-pedantic", "-Werror", "-fsyntax-only", "-isystem",
                str(tools.argos / "include"), *lua, "-I", ".", compiled.name + "_controller.cpp"], out)


BUILDS = {"python": build_python, "pipuck": build_pipuck, "c": build_c, "kilobot": build_kilobot,
          "capbot": build_capbot, "argos": build_argos}


@pytest.fixture(scope="module")
def tools():
    """The real kilolib and ARGoS (found or built as tests/targets/kilobot and tests/targets/argos do); without
    them the test skips, except in CI (CI=true), where it fails."""
    status, prefix, stderr = find_argos()
    if status == NO_ARGOS and os.environ.get("CI") != "true":
        pytest.skip("ARGoS not found: `make argos` builds it")
    assert status == 0, stderr
    return SimpleNamespace(kilolib=kilolib_or_skip(), argos=prefix)


def test_every_target_has_a_build():
    assert set(BUILDS) == set(api.TARGETS)


@pytest.mark.slow
@given(supervisor_sets(max_events=6, max_supervisors=3, max_states=3), MODEL_NAMES)
# Found: at one event, avr-gcc -Os (the streaming Kilobot build) took the image swap's name map
# for uninitialised (-Werror=maybe-uninitialized in runtime_c/swarmvm.c; the map is zeroed now).
@example(SupervisorSet(("auto",), (0,), (0,), (frozenset({"auto"}),), (((),),), (0,)), "message")
# Found: the ARGoS image's namespace was the model name, and a model named like a C library
# identifier (uint8_t, printf, time) redeclared it; it is <model>_image now.
@example(SupervisorSet(("auto",), (0,), (0,), (frozenset({"auto"}),), (((),),), (0,)), "uint8_t")
def test_generated_code_compiles_on_every_target_or_gen_names_the_target(tools, supervisor_set, name):
    refused, built = {}, {}
    with tempfile.TemporaryDirectory() as folder:
        path = write_set(folder, supervisor_set)
        for target in sorted(BUILDS):
            out = Path(folder) / target
            try:
                generated = api.generate_target([str(path)], target, str(out), name=name)
            except api.InputError as error:
                refused[target] = str(error)
                continue
            built[target] = BUILDS[target](out, generated.compiled, tools)
    event("targets that generated: %d of %d" % (len(built), len(BUILDS)))
    assert {t: problem for t, problem in built.items() if problem} == {}
    assert all("\n" not in message for message in refused.values()), refused
    if built:       # refused by some targets only: each refusal says which target it is about
        assert {t: m for t, m in refused.items() if t not in m} == {}


def test_the_replay_finds_what_a_local_supervisor_refuses(tmp_path):
    """The check of (b) can fail: EV_c is possible in state 0 only, EV_u nowhere."""
    path = tmp_path / "m.yaml"
    path.write_text(supervisor_yaml(["c", "u"], [1, 0], [{"c", "u"}], [[[("c", 1)], []]]))
    assert replay_on_the_file(path, ["1 EV_c 1 0", "2 EV_u 1 1"]) == []
    assert len(replay_on_the_file(path, ["1 EV_c 1 0", "2 EV_c 1 1"])) == 1      # c disabled in state 1
    assert len(replay_on_the_file(path, ["1 EV_c 1 0", "2 EV_u 1 0"])) == 1      # a violation not counted
    assert len(replay_on_the_file(path, ["1 EV_c 1 0", "2 - 0 0"])) == 1         # a state the file cannot be in
