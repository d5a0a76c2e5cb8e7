"""One naming rule for everything swarmvm generates, on every target.

Event and model names come from files other people wrote; every identifier and message the
generated code uses is derived from them here, once, and checked for collisions before anything
is written:

- callbacks: ``<kind>_<stem>`` with the runtime's :func:`callback_stem` (``_x`` -> ``received_x``),
  in C prefixed by the model name (``<model>_on_<stem>``), in C++ capitalised (``On_<stem>``);
- messages: a public event travels as its *message name*, the event name without the leading
  ``_`` of the receive side (``EV_x`` sends "x", ``EV__x`` receives it). Kilobot messages carry
  its first 9 characters, ARGoS range-and-bearing packets a 16-bit :func:`message_code`, Pi-puck
  broadcasts the whole name;
- the model name prefixes generated files, types, namespaces and functions and never stands
  alone as an identifier (the ARGoS image is ``<model>_image::kImage``), so no name a C or C++
  library declares can clash with it; it must be an ASCII identifier that no language or
  runtime keeps for itself.

A rule one target only needs lives in that target's record (its ``rules``) and refuses the
model for that target alone, naming it (swarmvm.targets.generate; ``swarmvm check --target T``
applies them up front): the Kilobot's 9-byte messages (swarmvm.targets.kilobot), ARGoS's 16-bit
message codes and C++'s reservation of identifiers holding ``__`` (swarmvm.targets.argos)."""

import keyword
import os
import re
from dataclasses import dataclass

from ..boundary.errors import InputError
from .model import Model
from .runtime_files import python_vm


def callback_stem(name: str) -> str:
    """The runtime's rule for the part of a callback's name that names its event (``_x`` ->
    ``received_x``): defined once, in the Python VM, which is loaded on first use rather than
    when this module is imported."""
    stem: str = python_vm().callback_stem(name)
    return stem


_C_CPP_KEYWORDS = frozenset("""
alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t char32_t
class compl concept const consteval constexpr constinit const_cast continue co_await co_return co_yield
decltype default delete do double dynamic_cast else enum explicit export extern false float for friend
goto if inline int long mutable namespace new noexcept not not_eq nullptr operator or or_eq private
protected public register reinterpret_cast requires restrict return short signed sizeof static
static_assert static_cast struct switch template this thread_local throw true try typedef typeid
typename union unsigned using virtual void volatile wchar_t while xor xor_eq
NULL EOF main errno assert offsetof bool true false
""".split())
FILE_NAME_BYTES = 255          # file systems allow file names of 255 bytes
# The longest file name gen writes is <model>_controller.cpp.new (a drifted ARGoS controller's fresh
# skeleton).
MAX_MODEL_NAME = FILE_NAME_BYTES - len("_controller.cpp.new")
# Prefixes the runtimes own: a model named like them would redefine runtime symbols. Compared in
# any case (the runtimes have svm_* functions and SVM_* macros), except SCT: the C compatibility
# layer's SCT_* functions clash with a model SCT only (SCT_vm), and the Python SCT names its own "sct".
_RUNTIME_PREFIXES = ("svm", "swarmvm", "kilo")
_CASE_SENSITIVE_PREFIXES = ("SCT",)


# A file named for what it is, not for its model: its folder names the model (the OpenSwarm
# projects keep each role's supervisor.yaml in a folder named for the role).
GENERIC_STEMS = ("supervisor",)


def default_stem(path: str) -> str:
    """The model's name when none is given: the input's file stem, or its folder's name for a
    file of a generic stem (``worker/supervisor.yaml`` is ``worker``); the naming rule
    (:func:`file_stem`) then makes either a valid name."""
    stem = os.path.splitext(os.path.basename(path))[0]
    folder = os.path.basename(os.path.dirname(os.path.abspath(path)))
    return folder if stem.lower() in GENERIC_STEMS and folder else stem


# Names Windows keeps for devices, in any case and with any extension (CON.svm is the console):
# a file so named cannot be checked out or built there.
WINDOWS_DEVICES = frozenset(["CON", "PRN", "AUX", "NUL", *("COM%d" % n for n in range(10)),
                             *("LPT%d" % n for n in range(10))])


def file_stem(stem: str, source: str, key: str = "--name") -> str:
    """``stem`` as the model's name in file names: every character outside [A-Za-z0-9_] made
    ``_``, ``m_`` before a leading digit (so no name ends in a dot or a space, which Windows
    drops). InputError (naming ``key``, the option that gave it) for a Windows device name
    (:data:`WINDOWS_DEVICES`), or when the result is longer than MAX_MODEL_NAME, so that every file named after it fits 255
    bytes. What `export` and `synth` name their files by: files, not code, so any word will do."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", stem)
    name = "m_" + name if name[:1].isdigit() else name
    if name.upper() in WINDOWS_DEVICES:
        raise InputError(source, key, "model name %r is a device name on Windows (%s.svm could not be checked out "
                         "or built there): give another with %s" % (name, name, key))
    if len(name) > MAX_MODEL_NAME:
        raise InputError(source, key, "model name of %d characters: at most %d, so that the generated file names "
                         "fit %d bytes: give a shorter one with %s" % (len(name), MAX_MODEL_NAME, FILE_NAME_BYTES, key))
    return name


def model_identifier(stem: str, source: str) -> str:
    """The model name as used in generated identifiers and file names: :func:`file_stem`, and
    InputError when it is a keyword of C, C++ or Python or starts like the runtimes' own symbols."""
    name = file_stem(stem, source)
    lowered = name.lower()
    if not name or name in _C_CPP_KEYWORDS or keyword.iskeyword(name):
        raise InputError(source, "--name", "model name %r is reserved in C, C++ or Python: give another with --name" % name)
    if any(lowered == p or lowered.startswith(p + "_") for p in _RUNTIME_PREFIXES) or \
            any(name == p or name.startswith(p + "_") for p in _CASE_SENSITIVE_PREFIXES):
        raise InputError(source, "--name", "model name %r collides with the runtime's own %s_* symbols: "
                         "give another with --name" % (name, name.split("_")[0]))
    return name


def message_name(name: str, controllable: bool) -> str:
    """The message a public event sends (controllable) or receives (uncontrollable ``_x``)."""
    return name[1:] if not controllable and name.startswith("_") else name


def fnv1a(text: str) -> int:
    """FNV-1a (32 bits) of a text: message codes here, and the ARGoS controller's per-robot VM
    seed (random seed XOR FNV-1a of the robot id, swarmvm::robot_seed in swarmvm_argos.hpp)."""
    value = 2166136261
    for byte in text.encode("utf-8"):
        value = ((value ^ byte) * 16777619) & 0xFFFFFFFF
    return value


def message_code(message: str) -> int:
    """16-bit code of a message on ARGoS's range-and-bearing: FNV-1a of the name folded to 16
    bits; 0 means "no message" on the wire, so it becomes 1."""
    value = fnv1a(message)
    return ((value >> 16) ^ (value & 0xFFFF)) or 1


@dataclass(frozen=True)
class EventNames:
    """Every name one event gets in generated code."""
    index: int
    name: str                  # bare name, as in the model
    const: str                 # EV_<name>
    stem: str                  # callback stem
    controllable: bool
    public: bool
    message: str | None        # message name of a public event
    code: int | None           # its 16-bit ARGoS code


def event_names(model: Model) -> list[EventNames]:
    """The names of every event, in model order; InputError naming the two events when two
    callbacks would be one (every target names callbacks by this rule)."""
    result: list[EventNames] = []
    stems: dict[str, str] = {}
    for i, name in enumerate(model.events):
        controllable, public = bool(model.controllable[i]), bool(model.public[i])
        stem = callback_stem(name)
        other = stems.setdefault(stem, name)
        if other != name:
            raise InputError(model.source, "events", "EV_%s and EV_%s would both have the callbacks *_%s: rename one"
                             % (other, name, stem), "event EV_%s" % name)
        message = message_name(name, controllable) if public else None
        code = message_code(message) if message is not None else None
        result.append(EventNames(i, name, "EV_" + name, stem, controllable, public, message, code))
    return result
