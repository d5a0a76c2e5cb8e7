"""The fuzz targets over swarmvm's readers: one function per reader taking the bytes of a file.

The property every reader must have (issue 12, docs/fuzzing.md): any input either loads or is
refused with the project's own one-line error, :class:`swarmvm.boundary.errors.InputError` (what the
command line prints as ``swarmvm: error: ...`` with exit status 2); the Python runtime's own
reader refuses with its :class:`ImageError`. Any other exception escapes the target and is a
finding; libFuzzer's timeout and memory limit catch a hang or unbounded memory. Images and
supervisors that load are also run for a few steps, because a reader that accepts what the VM
cannot run (an index out of range) is a finding too.

The same functions replay the regression cases (tests/fuzz/test_fuzz_regressions.py), so a
kept finding runs exactly as the fuzzer ran it, without a fuzzer."""

import ctypes
import functools
import os
import subprocess
import tempfile
from pathlib import Path
from typing import Callable, Dict

import nadzoru_c_form
from swarmvm import api
from swarmvm.boundary.errors import InputError
from swarmvm.readers.lua_literal import LuaSyntaxError, parse_lua_table
from swarmvm.compiler.runtime_files import RUNTIME_C, image_format, python_vm

F = image_format()
VM = python_vm()
ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus"
REGRESSIONS = Path(__file__).resolve().parent / "regressions"
SCRIPT_SUPERVISOR = CORPUS / "openswarm" / "energy_worker.yaml"
STEPS = 16          # steps run on an image that loads
POLICIES = ("uniform", "first", "weighted")
# The C runtime's limits at the format's own maxima: every image the format allows is within them.
C_LIMITS = ["-DSVM_MAX_EVENTS=255", "-DSVM_MAX_SUPERVISORS=255", "-DSVM_MAX_STATES=65535"]


@functools.lru_cache(maxsize=None)
def _workdir() -> Path:
    """One private folder per process for the files the readers are given (they read paths)."""
    return Path(tempfile.mkdtemp(prefix="swarmvm-fuzz-"))


def _as_file(data: bytes, suffix: str) -> str:
    """``data`` written to this process's input file of that suffix (rewritten each call)."""
    path = _workdir() / ("input" + suffix)
    path.write_bytes(data)
    return str(path)


def resealed(data: bytes) -> bytes:
    """``data`` with the image header's length field and the checksum made to fit, so that a
    mutated image reaches the layout checks instead of stopping at LENGTH or CRC."""
    if len(data) < F.MIN_IMAGE_SIZE or len(data) > F.MAX_IMAGE_SIZE:
        return data
    body = bytearray(data[:-F.CRC_SIZE])
    at = F.OFFSETS["length"]
    body[at:at + 2] = len(data).to_bytes(2, "little")
    return bytes(body) + F.crc16(bytes(body)).to_bytes(F.CRC_SIZE, "little")


def _scripts(image) -> list:
    """Event rows over the image's uncontrollable events: none, all, then alternating halves."""
    uncontrollable = [e for e in range(image.num_events) if not image.controllable >> e & 1]
    rows = [set(), set(uncontrollable)]
    rows += [{e for k, e in enumerate(uncontrollable) if (k + step) % 2} for step in range(STEPS - 2)]
    return rows


def refused(exc: InputError) -> None:
    """An InputError is the property only when it is one printable line (the CLI prints it as
    one: no line break, and no control character of the input reaches the terminal)."""
    assert str(exc).isprintable(), "a refusal that is not one printable line: %r" % str(exc)


def run_image(image) -> None:
    """Step a loaded image under every policy and input mode, as ``swarmvm trace`` does."""
    for policy in POLICIES:
        for inputs in VM.INPUT_MODES:
            VM.replay(VM.VM(image, inputs=inputs, policy=policy), _scripts(image))


def _supervisor(suffix: str) -> Callable[[bytes], None]:
    """A target over one supervisor reader (chosen by the file's suffix): the file compiled as
    ``swarmvm check`` and ``gen`` compile it, then its image read back and run for a few steps."""
    def target(data: bytes) -> None:
        path = _as_file(data, suffix)
        try:
            compiled = api.compile_model([path])
        except InputError as exc:
            refused(exc)
            return
        run_image(VM.Image.parse(compiled.image))
    target.__doc__ = "A %s file: checks and compiles, or an InputError." % suffix
    target.suffix = suffix     # tests/readers/test_registry.py: every suffix swarmvm reads is fuzzed
    return target


@functools.lru_cache(maxsize=None)
def _c_validate():
    """The C runtime's svm_validate (runtime_c/swarmvm.c as a shared library, built once)."""
    library = _workdir() / "libswarmvm.so"
    subprocess.run(["gcc", "-std=c99", "-O1", "-shared", "-fPIC", *C_LIMITS, "-I", str(RUNTIME_C),
                    str(RUNTIME_C / "swarmvm.c"), "-o", str(library)], check=True)
    validate = ctypes.CDLL(str(library)).svm_validate
    validate.argtypes, validate.restype = [ctypes.c_char_p, ctypes.c_uint16, ctypes.c_uint8], ctypes.c_int
    return validate


def svm_runtime(data: bytes) -> None:
    """The Python runtime's reader (swarmvm_format.Image.parse): an image, or an ImageError
    with the code the C runtime's reader gives the same bytes (``check`` must not accept what
    a robot refuses). Each input is tried as it is and resealed (length and checksum fitted)."""
    for raw in dict.fromkeys((data, resealed(data))):
        try:
            image, code = F.Image.parse(raw), F.ErrorCode.OK
        except F.ImageError as exc:
            image, code = None, exc.code
        if len(raw) <= F.MAX_IMAGE_SIZE:
            c_code = _c_validate()(raw, len(raw), 0)
            assert c_code == code, "the C reader gives %d, the Python reader %d (%s)" % (c_code, code, code.name)
        if image is not None:
            run_image(image)


def svm_swarmvm(data: bytes) -> None:
    """swarmvm's reader of ``.svm`` files (``swarmvm check`` and ``trace`` on an image): an
    image that runs, or an InputError. Tried as it is and resealed."""
    for raw in dict.fromkeys((data, resealed(data))):
        path = _as_file(raw, ".svm")
        try:
            api.check([path])
            image = api.read_image(path)
        except InputError as exc:
            refused(exc)
            continue
        run_image(image)


@functools.lru_cache(maxsize=None)
def _script_image() -> str:
    """The .svm image scripts are replayed on (the example worker, with names)."""
    compiled = api.compile_model([str(SCRIPT_SUPERVISOR)])
    return _as_file(compiled.image, ".script.svm")


def script(data: bytes) -> None:
    """The event-script reader, as ``swarmvm trace`` uses it: a trace, or an InputError."""
    path = _as_file(data, ".txt")
    try:
        for _ in api.trace([_script_image()], path):
            pass
    except InputError as exc:
        refused(exc)


def lua_literal(data: bytes) -> None:
    """The Lua literal reader under the ``.nza`` reader (swarmvm.readers.lua_literal), alone and so
    reached by every input rather than only those that decode and frame as an automaton: a
    table, or its LuaSyntaxError (the ``.nza`` reader turns that into one InputError line)."""
    try:
        table = parse_lua_table(data.decode("utf-8", "surrogateescape"))
    except LuaSyntaxError as exc:
        assert "\n" not in exc.message, "a refusal of more than one line: %r" % exc.message
        return
    assert isinstance(table, dict)


READERS: Dict[str, Callable[[bytes], None]] = {
    "yaml": _supervisor(".yaml"),
    "xml": _supervisor(".xml"),
    "xmd": _supervisor(".xmd"),
    "nza": _supervisor(".nza"),
    "lua": lua_literal,
    "gen": _supervisor(".gen"),
    "c": _supervisor(".c"),
    "svm_runtime": svm_runtime,
    "svm": svm_swarmvm,
    "svm_supervisor": _supervisor(".svm"),
    "script": script,
}


def seeds(reader: str) -> Dict[str, bytes]:
    """The seed corpus of a reader: every file of its kind in the test corpus and examples
    ({name: bytes}); images are packed from the corpus's supervisors."""
    if reader in ("svm", "svm_runtime", "svm_supervisor"):
        return {p.stem + ".svm": api.compile_model([str(p)]).ordered_image for p in sorted(CORPUS.glob("*/*.yaml"))}
    if reader == "c":
        return {p.stem + ".c": nadzoru_c_form.inline(nadzoru_c_form.read_yaml(p)).encode("ascii")
                for p in sorted(CORPUS.glob("*/*.yaml")) if "sup_data_prob" not in p.read_text(encoding="utf-8")}
    if reader == "script":
        return {"energy_worker.txt": api.make_script([str(SCRIPT_SUPERVISOR)], 20, 1).encode("ascii")}
    suffix = ".nza" if reader == "lua" else "." + reader
    found = sorted(p for folder in (CORPUS, ROOT / "tests" / "models", ROOT / "examples")
                   for p in folder.rglob("*" + suffix) if p.is_file())
    return {"%02d_%s" % (k, p.name): p.read_bytes() for k, p in enumerate(found)}


def cleanup() -> None:
    """Remove this process's input files."""
    folder = _workdir()
    for entry in folder.iterdir():
        entry.unlink()
    os.rmdir(folder)
    _workdir.cache_clear()
    _c_validate.cache_clear()
