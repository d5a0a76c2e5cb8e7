"""The targets ``swarmvm gen --target`` knows: which templates render to which files.

A target differs from another only in its templates and the runtime files it ships; the
tables and image are the same for all. A file entry is (template, output name, keep): output
names may use ``{name}``; ``keep`` marks user-edited files that are never overwritten."""

import dataclasses
from dataclasses import dataclass, field
from importlib.abc import Traversable
from typing import Callable

from .. import __version__
from ..boundary.errors import InputError
from ..boundary.escape import UnsafeText
from ..compiler.pipeline import Compiled
from ..compiler.render import context, render
from ..compiler.runtime_files import (
    RUNTIME_C,
    RUNTIME_CPP,
    RUNTIME_FORMAT_PY,
    RUNTIME_LEARN_PY,
    RUNTIME_PY,
    RUNTIME_PY_DIR,
)
from . import argos, kilobot
from . import values as target_values
from .values import runtime_files

TemplateFile = tuple[str, str, bool]        # (template, output name, keep)
RuntimeCopy = tuple[Traversable, str]       # (source path, output name)


@dataclass(frozen=True)
class Target:
    description: str
    templates: tuple[TemplateFile, ...]
    copies: tuple[RuntimeCopy, ...] = field(default=())
    learned_templates: tuple[TemplateFile, ...] = field(default=())   # added by --learned-check (docs/learning.md)
    learned_copies: tuple[RuntimeCopy, ...] = field(default=())
    prepare: Callable[[Compiled], dict[str, object]] | None = None   # extra template values; InputError if unfit
    values: Callable[[Compiled], dict[str, object]] | None = None    # template values decided in Python
    keeps_order: bool = False            # its image keeps the source order (the Python SCT's exact mode)


# The Python VM and the image format it reads (swarmvm_vm imports swarmvm_format), and what the
# apps (python3 -m <name>_app) share: their options and fixed-rate loop.
PY_RUNTIME_COPIES = ((RUNTIME_PY, "swarmvm_vm.py"), (RUNTIME_FORMAT_PY, "swarmvm_format.py"),
                     (RUNTIME_PY_DIR / "swarmvm_app.py", "swarmvm_app.py"))


def c_copies(*groups: str, folder: str = "") -> tuple[RuntimeCopy, ...]:
    """The C runtime's files of ``groups`` (target_values.RUNTIME_GROUPS) as copies into ``folder``."""
    return tuple((RUNTIME_C / n, folder + n) for n in runtime_files(*groups))


# What every C target ships: the VM, Nadzoru 2's C API over it, the canonical trace line.
C_RUNTIME_GROUPS = ("core", "sct", "trace")

TARGETS = {
    "python": Target(
        "Python VM: table module, app module binding the callbacks, controller skeleton, the runtime (stdlib only)",
        templates=(("python/tables.py.j2", "{name}_tables.py", False),
                   ("python/app.py.j2", "{name}_app.py", False),
                   ("python/controller.py.j2", "{name}_controller.py", True)),
        copies=PY_RUNTIME_COPIES,
        learned_templates=(("python/learned.py.j2", "{name}_learned.py", False),),
        learned_copies=((RUNTIME_LEARN_PY, "swarmvm_learn.py"),),
        keeps_order=True),
    "argos": Target(
        "ARGoS e-puck controller (C++17): image header, generated CCI_Controller base class, controller skeleton, CMakeLists.txt, example .argos",
        templates=(("argos/image.hpp.j2", "{name}_image.hpp", False),
                   ("argos/base.h.j2", "{name}_base.h", False),
                   ("argos/controller.h.j2", "{name}_controller.h", True),
                   ("argos/controller.cpp.j2", "{name}_controller.cpp", True),
                   ("argos/CMakeLists.txt.j2", "CMakeLists.txt", True),
                   ("argos/experiment.argos.j2", "{name}.argos", True)),
        copies=tuple((RUNTIME_CPP / n, n) for n in ("swarmvm.hpp", "swarmvm_argos.hpp", "swarmvm_argos_controller.hpp",
                                                     "swarmvm_argos_report.hpp", "swarmvm_argos.cmake")),
        prepare=argos.prepare),
    "pipuck": Target(
        "Pi-puck controller (Python): tables, the Python VM, robot adapters (real and --sim), fixed-rate app, controller skeleton",
        templates=(("python/tables.py.j2", "{name}_tables.py", False),
                   ("pipuck/app.py.j2", "{name}_app.py", False),
                   ("pipuck/controller.py.j2", "{name}_controller.py", True)),
        copies=PY_RUNTIME_COPIES + ((RUNTIME_PY_DIR / "swarmvm_pipuck.py", "swarmvm_pipuck.py"),),
        keeps_order=True),
    "c": Target(
        "C VM (C99, host or microcontroller): tables with the image as a const array, dispatch glue, control loop, Makefile, controller skeleton",
        templates=(("c/tables.h.j2", "{name}_tables.h", False),
                   ("c/tables.c.j2", "{name}_tables.c", False),
                   ("c/main.c.j2", "{name}_main.c", False),
                   ("c/Makefile.j2", "Makefile", False),
                   ("c/controller.c.j2", "{name}_controller.c", True)),
        copies=c_copies(*C_RUNTIME_GROUPS),
        values=target_values.c_values),
    "kilobot": Target(
        "Kilobot application (kilolib, ATmega328P): tables in PROGMEM, messages as public events, new images streamed over messages, Makefile, controller skeleton",
        templates=(("c/tables.h.j2", "{name}_tables.h", False),
                   ("kilobot/tables.c.j2", "{name}_tables.c", False),
                   ("kilobot/app.h.j2", "{name}_app.h", False),
                   ("kilobot/app.c.j2", "{name}_app.c", False),
                   ("kilobot/Makefile.j2", "Makefile", False),
                   ("kilobot/controller.c.j2", "{name}_controller.c", True)),
        copies=c_copies(*C_RUNTIME_GROUPS, "stream", "kilobot", "kilobot_eeprom", "learn"),
        prepare=kilobot.prepare, values=target_values.kilobot_values),
    "capbot": Target(
        "CapBot application (Zephyr, nRF52840): CMakeLists.txt, prj.conf, main stepping the VM every 100 ms, tables, controller skeleton on the CapBot API",
        templates=(("capbot/CMakeLists.txt.j2", "CMakeLists.txt", False),
                   ("capbot/prj.conf.j2", "prj.conf", False),
                   ("capbot/learned.conf.j2", "learned.conf", False),
                   ("capbot/main.c.j2", "src/main.c", False),
                   ("c/tables.h.j2", "src/{name}_tables.h", False),
                   ("c/tables.c.j2", "src/{name}_tables.c", False),
                   ("capbot/controller.c.j2", "src/{name}_controller.c", True)),
        copies=c_copies(*C_RUNTIME_GROUPS, "logic_page", "learn", "store_zephyr", folder="src/"),
        values=target_values.capbot_values),
}


def generate(compiled: Compiled, target: str, **options: object) -> dict[str, tuple[bytes, bool]]:
    """{output name: (bytes, keep)} for one target: rendered templates, runtime copies, image."""
    spec = TARGETS[target]
    name = compiled.name        # refused (InputError) for every target alike, before any target's own checks
    if spec.keeps_order:
        compiled = dataclasses.replace(compiled, image=compiled.ordered_image)
    try:
        extra = spec.prepare(compiled) if spec.prepare else {}
    except InputError as error:         # refused for this target only: say which
        raise InputError(error.file, error.key, "target %s: %s" % (target, error.message), error.where)
    if spec.values:
        extra = dict(extra, **spec.values(compiled))
    values = context(compiled, target=target, **dict(options, **extra))
    templates, copies = spec.templates, spec.copies
    if options.get("learned_checks"):
        templates, copies = templates + spec.learned_templates, copies + spec.learned_copies
    files = {"%s.svm" % name: (compiled.image, False)}
    for template, output, keep in templates:
        rel = output.format(name=name)
        try:
            files[rel] = (render(template, values), keep)
        except UnsafeText as error:     # text that file's language cannot hold (swarmvm.boundary.escape)
            raise InputError(compiled.model.source, "--target", "target %s: %s: %s" % (target, rel, error))
    for source, output in copies:
        files[output.format(name=name)] = (copy_banner(output) + source.read_bytes(), False)
    return files


def copy_banner(output: str) -> bytes:
    """The first line of a runtime file copied into a target: where it comes from, and that
    ``swarmvm gen`` owns it (rewrites it on every run)."""
    text = "Copied from the swarmvm %s runtime by swarmvm gen, which rewrites it: do not edit." % __version__
    return ("# %s\n" % text if output.endswith((".py", ".cmake")) else "/* %s */\n" % text).encode("ascii")
