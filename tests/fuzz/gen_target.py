"""The fuzz target over ``swarmvm gen`` for every target, with the generated code compiled.

The input bytes are decoded (atheris' FuzzedDataProvider) into a random local-modular
supervisor set whose event and model names come from awkward pools too (C, C++ and Python
keywords, ``stream``, ``x`` beside ``_x``/``received_x``, the runtime's ``svm``/``svm_sct``,
``NULL``, 255-character and non-ASCII names); it is written as a Nadzoru 2 ``supervisor.yaml``
(swarmvm.models.export.to_yaml) and generated for every target. The property (issue 12): for each
target either a clear project error (an InputError of one line, and nothing written), or code
that compiles: py_compile for python and pipuck; the c and kilobot targets' sources, as their
generated Makefiles list them, with its limits, under the strict warnings of
tests/targets/c/test_c_warnings.py (gcc; avr-gcc with kilolib's flags against the real kilolib);
capbot's sources with arm-none-eabi-gcc against firmware/capbot's Zephyr and CapBot
declarations; argos' controller with g++ -fsyntax-only against the real ARGoS headers.
Compiling takes seconds, so this target runs few iterations."""

import functools
import json
import keyword
import py_compile
import re
import shutil
import subprocess
import tempfile
from fractions import Fraction
from pathlib import Path

import atheris

from targets.argos.argos_project import find_argos
from targets.c.test_c_warnings import ARM, COMPILERS, compile_only
from conformance.qemu_harness import CAPBOT
from fuzz.readers import refused
from targets.kilobot.needs import kilolib_or_skip
from swarmvm import api
from swarmvm.boundary.errors import InputError
from swarmvm.models.export import to_yaml
from swarmvm.compiler.model import CanonicalSupervisor, Model
from swarmvm.targets import TARGETS

MAX_EVENTS, MAX_SUPERVISORS, MAX_STATES = 8, 3, 4
PLAIN = ["a", "b", "go", "stop", "msg", "_msg", "tick", "Z9"]
# The C11 and C++20 keywords and a few predefined names, written out here rather than taken from
# swarmvm.compiler.naming: the fuzzer must not share a gap in the compiler's own list.
C_CPP_WORDS = """alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
char32_t class compl concept const consteval constexpr constinit const_cast continue co_await co_return co_yield
decltype default delete do double dynamic_cast else enum explicit export extern false final float for friend goto
if import inline int long module mutable namespace new noexcept not not_eq nullptr operator or or_eq override
private protected public register reinterpret_cast requires restrict return short signed sizeof static
static_assert static_cast struct switch template this thread_local throw true try typedef typeid typename union
unsigned using virtual void volatile wchar_t while xor xor_eq _Alignas _Atomic _Bool _Complex _Generic
_Noreturn _Static_assert _Thread_local NULL EOF errno assert stdin stdout FILE size_t uint8_t int main
printf exit""".split()
AWKWARD = (C_CPP_WORDS + sorted(keyword.kwlist) + sorted(keyword.softkwlist)
           + ["stream", "x", "_x", "received_x", "svm", "svm_sct", "NULL", "main", "kilo_x", "swarmvm", "__x",
              "_", "", "1a", "EV_x", "a" * 255, "b" * 254 + "_", "\u00e9t\u00e9", "na\u00efve"])
PLAIN_MODEL_NAMES = ["a", "worker", "m2"]
# Input file names, whose stem is the model name when --name is not given (issue 23): fragments
# that end a comment, a string or a line in the languages gen writes, and Make/CMake commands.
FILE_STEMS = ["fuzz", "x\nall:\n\ttouch CANARY\n#", 'a"""b', "*/ x /*", "a\\", "??/", "$(shell x)", '")\nmessage(x)#',
              "--", "\x1b[2J", "\u202e", "cci", "t\u00e9st"]
MODEL_NAMES = AWKWARD + ["a-b", "m" * 200, "time", "signal", "FILE", "size_t", "printf", "stdin", "kilo", "svm_x"]
PROBABILITIES = (Fraction(1), Fraction(1, 2), Fraction(1, 3), Fraction(0))
LIMITS = re.compile(r"-DSVM_MAX_\w+=\d+")


def _pick(fdp, pool):
    return pool[fdp.ConsumeIntInRange(0, len(pool) - 1)]


def decode(data: bytes):
    """(Model, model name or None, input file name) from the fuzzer's bytes: every count, name,
    flag, alphabet and transition is drawn from them. The model is not checked here: swarmvm's
    reader is."""
    fdp = atheris.FuzzedDataProvider(data)
    n = fdp.ConsumeIntInRange(1, MAX_EVENTS)
    events: list = []
    for k in range(n):      # a name drawn twice becomes a plain one: duplicates only test the reader
        name = _pick(fdp, PLAIN if fdp.ConsumeBool() else AWKWARD)
        events.append(name if name not in events else "e%d" % k)
    controllable = tuple(fdp.ConsumeBool() for _ in range(n))
    public = tuple(fdp.ConsumeBool() for _ in range(n))
    probabilistic = fdp.ConsumeBool()
    supervisors = []
    for _ in range(fdp.ConsumeIntInRange(1, MAX_SUPERVISORS)):
        alphabet = frozenset(e for e in range(n) if fdp.ConsumeBool())
        count = fdp.ConsumeIntInRange(1, MAX_STATES)
        states = tuple(tuple((e, fdp.ConsumeIntInRange(0, count - 1),
                              _pick(fdp, PROBABILITIES) if probabilistic and controllable[e] else None)
                             for e in sorted(alphabet) if fdp.ConsumeBool())
                       for _ in range(count))
        supervisors.append(CanonicalSupervisor(alphabet, states))
    model = Model("fuzz.yaml", tuple(events), controllable, public, tuple(supervisors), probabilistic)
    name = _pick(fdp, PLAIN_MODEL_NAMES if fdp.ConsumeBool() else MODEL_NAMES) if fdp.ConsumeBool() else None
    stem = _pick(fdp, FILE_STEMS) if fdp.ConsumeBool() else fdp.ConsumeUnicodeNoSurrogates(24)
    return model, name, (stem.replace("/", "_").replace("\0", "_") or "fuzz") + ".yaml"


@functools.lru_cache(maxsize=None)
def _argos_includes() -> tuple:
    """-isystem options for ARGoS's headers and the Lua headers they include (as the generated
    swarmvm_argos.cmake finds them: ARGoS built with Lua needs <lua.h>)."""
    status, prefix, stderr = find_argos()
    if prefix is None:
        raise RuntimeError("ARGoS not found (scripts/argos.sh exit %d): %s" % (status, stderr[-500:]))
    lua = subprocess.run(["pkg-config", "--cflags-only-I", "lua5.3"], capture_output=True, text=True, check=True)
    folders = [str(prefix / "include")] + [flag[2:] for flag in lua.stdout.split()]
    return tuple(option for folder in folders for option in ("-isystem", folder))


def _make_variable(makefile: Path, variable: str) -> list:
    """The words of ``VARIABLE = ...`` in a generated Makefile, a word ``$(OTHER)`` replaced by
    OTHER's words (the Kilobot's SOURCES start with ``$(MAIN)``, the program a user may swap)."""
    match = re.search(r"^%s\s*=(.*)$" % variable, makefile.read_text(), re.MULTILINE)
    assert match, "%s: no %s" % (makefile, variable)
    words = []
    for word in match.group(1).split():
        reference = re.fullmatch(r"\$\((\w+)\)", word)
        words += _make_variable(makefile, reference.group(1)) if reference else [word]
    return words


def _compile_c(folder: Path, command: list, includes: list, scratch: Path) -> list:
    """The sources the generated Makefile builds, compiled with its limits and the strict warnings."""
    makefile = folder / "Makefile"
    sources = [folder / s for s in _make_variable(makefile, "SOURCES")]
    limits = LIMITS.findall(makefile.read_text())
    return compile_only(command + limits, sources, [folder, *includes], scratch)


def compile_target(target: str, folder: Path, scratch: Path) -> list:
    """The compiler's complaints about a generated target (empty: it compiles)."""
    if target in ("python", "pipuck"):
        complaints = []
        for source in sorted(folder.glob("*.py")):
            try:
                py_compile.compile(str(source), cfile=str(scratch / "out.pyc"), doraise=True)
            except py_compile.PyCompileError as exc:
                complaints.append(str(exc))
        return complaints
    if target == "c":
        return _compile_c(folder, COMPILERS["gcc"], [], scratch)
    if target == "kilobot":
        return _compile_c(folder, COMPILERS["avr-gcc-kilobot-flash-only"], [kilolib_or_skip()], scratch)
    if target == "capbot":
        limits = LIMITS.findall((folder / "CMakeLists.txt").read_text())
        return compile_only(["arm-none-eabi-gcc", *ARM, "-O2", *limits], sorted((folder / "src").glob("*.c")),
                            [folder / "src", CAPBOT], scratch)
    if target == "argos":
        proc = subprocess.run(["g++", "-std=c++17", "-fsyntax-only", "-Wall", "-Wextra", "-pedantic", "-Werror",
                               *_argos_includes(), "-I", str(folder),
                               *map(str, sorted(folder.glob("*.cpp")))], capture_output=True, text=True)
        return [proc.stderr.strip() or "exit %d" % proc.returncode] if proc.returncode or proc.stderr.strip() else []
    raise AssertionError("no compiler known for target %s" % target)


def check_supervisor(text: str, name: str | None, file: str = "fuzz.yaml", targets=tuple(sorted(TARGETS))) -> list:
    """The property for one supervisor.yaml text in a file named ``file`` generated under the
    model name ``name`` (None: the file's stem) for each of ``targets``; AssertionError naming
    the target otherwise. The targets whose code was generated and compiled (the others refused
    the model)."""
    compiled = []
    scratch = Path(tempfile.mkdtemp(prefix="swarmvm-fuzz-gen-"))
    try:
        supervisor = scratch / file
        supervisor.write_text(text, encoding="utf-8")
        for target in targets:
            out = scratch / "out" / target
            try:
                api.generate_target([str(supervisor)], target, str(out), name=name)
            except InputError as exc:
                refused(exc)
                assert not out.exists(), "%s: refused (%s) but wrote %s" % (target, exc, sorted(out.rglob("*")))
                continue
            complaints = compile_target(target, out, scratch)
            assert not complaints, "%s (model %r): generated code does not compile:\n%s\n%s" % (
                target, name, "\n".join(complaints)[-3000:], text)
            compiled.append(target)
    finally:
        shutil.rmtree(scratch)
    return compiled


REGRESSION_HEADER = re.compile(r"\A# swarmvm gen (\{.*\})\n")


def regression_text(data: bytes) -> str:
    """A finding's input as the regression case kept in tests/fuzz/regressions/codegen/: the
    supervisor.yaml it decodes to, the model name and the file name as JSON in its first line.
    Kept decoded, so that the case stays what it was when the pools above change."""
    model, name, file = decode(data)
    return "# swarmvm gen %s\n%s" % (json.dumps({"name": name, "file": file}), to_yaml(model))


def check_regression(text: str) -> list:
    """Replay a kept case (:func:`regression_text`); the targets it compiled for."""
    match = REGRESSION_HEADER.match(text)
    assert match, 'a codegen case starts with \'# swarmvm gen {"name": NAME, "file": FILE}\''
    header = json.loads(match.group(1))
    return check_supervisor(text, header["name"], header["file"])


def compile_input(data: bytes) -> list:
    """The property for the fuzzer's bytes; the targets they compiled for."""
    model, name, file = decode(data)
    return check_supervisor(to_yaml(model), name, file)


def one_input(data: bytes) -> None:
    """The fuzz target (atheris wants nothing back)."""
    compile_input(data)


def seeds() -> dict:
    """A few inputs that decode to different shapes (libFuzzer mutates from there)."""
    return {"zeros": bytes(64), "ones": b"\xff" * 96, "ramp": bytes(range(128)),
            "ramp_down": bytes(range(255, 55, -1))}

