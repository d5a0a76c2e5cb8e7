"""The c target (templates/c/, docs/robots/c.md): the C VM with a host control loop and a
Makefile, for a host or any microcontroller a C99 compiler builds for."""

import posixpath
import re

from ..boundary.errors import InputError
from ..compiler.naming import MAX_MODEL_NAME, WINDOWS_DEVICES
from ..compiler.pipeline import Compiled
from ..compiler.render import context, render
from ..compiler.runtime_files import TEMPLATES, image_format
from .record import Readme, Target
from .values import C_RUNTIME_GROUPS, c_copies, headers, sources


def file_order(compiled: Compiled) -> dict[str, object]:
    """What the C API's exact mode (runtime_c/swarmvm_sct.h, SVM_SCT_EXACT=1) needs and the image
    (canonical: events by name, states breadth-first) does not keep, for every C-family target's
    tables: ``file_index`` (image event index -> its index in the supervisor file, the published
    EV_x) and, as the bytes of the arrays swarmvm_sct.h declares, ``file_events`` (the inverse:
    the image index of the file's event i), ``file_states`` (the file's number of each global
    state, u16 little-endian) and ``file_start`` (each supervisor's local state where the file
    starts it, its sup_current_state, u16 little-endian). From the ordered image's order section
    (a supervisor file read); from automata, which have no file order, the canonical order."""
    model = compiled.model
    parsed = image_format().Image.parse(compiled.ordered_image)
    index = list(parsed.order) if parsed.order is not None else list(range(len(model.events)))
    states = [n for sup in model.supervisors for n in (sup.input_states or range(len(sup.states)))]
    events = [0] * len(index)
    for image_event, file_event in enumerate(index):
        events[file_event] = image_event
    return dict(file_index=index, file_events=bytes(events), file_states=_u16(states),
                file_start=_u16([sup.start for sup in model.supervisors]))


def _u16(numbers: list[int]) -> bytes:
    return b"".join(n.to_bytes(2, "little") for n in numbers)


# What --sct-header takes: a C header's file name that is also an identifier's characters, so
# that its include guard is one and it reads the same on every file system.
HEADER_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\.h\Z")
TABLES_HEADER = "c/tables.h.j2"


def sct_header(compiled: Compiled, target: Target, header: str, files: dict[str, tuple[bytes, bool]]
               ) -> tuple[str, bytes]:
    """``gen --sct-header``: (output name, bytes) of a header called ``header`` beside the C
    tables, which brings all a published program's include gave it (EV_x, NUM_EVENTS,
    NUM_SUPERVISORS, the SCT_* prototypes) by including the generated tables header, so that
    the program's ``#include "sct_work_and_charge.h"`` stays as it is. InputError (key
    --sct-header) for a target without the C tables, a name that is not ``identifier.h``, a
    Windows device name, a name too long, or one that a file gen writes already has."""
    tables = [output for template, output, _ in target.templates if template == TABLES_HEADER]
    if not tables:
        raise InputError(compiled.source, "--sct-header", "target %s has no C tables to include: --sct-header is for "
                         "the C targets (c, kilobot, capbot)" % target.name)
    stem = header[:-2]
    if not HEADER_NAME.match(header) or stem.upper() in WINDOWS_DEVICES or len(stem) > MAX_MODEL_NAME:
        raise InputError(compiled.source, "--sct-header", "%r is not a header name gen writes: give a name of "
                         "letters, digits and _ ending in .h (at most %d characters before it, not a Windows device "
                         "name), e.g. sct_work_and_charge.h" % (header, MAX_MODEL_NAME))
    folder = posixpath.dirname(tables[0].format(name=compiled.name))
    output = posixpath.join(folder, header)
    if any(existing.lower() == output.lower() for existing in files):
        raise InputError(compiled.source, "--sct-header", "%s is a file gen writes itself: give another name" % header)
    values = context(compiled, target=target.name, guard=stem.upper())
    return output, render("c/sct_header.h.j2", values)


def values(compiled: Compiled) -> dict[str, object]:
    """The Makefile: the runtime it compiles (the core and Nadzoru's C API); the tables' file
    order (:func:`file_order`)."""
    return dict(runtime_sources=sources("core", "sct"), runtime_headers=headers("core", "sct"),
                **file_order(compiled))


TARGET = Target(
    "c",
    "C VM (C99, host or microcontroller): tables with the image as a const array, dispatch glue, control loop, Makefile, controller skeleton",
    templates=(("c/tables.h.j2", "{name}_tables.h", False),
               ("c/tables.c.j2", "{name}_tables.c", False),
               ("c/dispatch.c.j2", "{name}_dispatch.c", False),
               ("c/main.c.j2", "{name}_main.c", False),
               ("c/Makefile.j2", "Makefile", False),
               ("c/controller.c.j2", "{name}_controller.c", True)),
    template_folder=TEMPLATES / "c",
    page="robots/c.md",
    copies=c_copies(*C_RUNTIME_GROUPS),
    values=values,
    build=("make", "-s"),
    readme=Readme("c/readme.md.j2", (
        ("{name}_tables.[ch]", "the table image as a C array and its loader, event constants"),
        ("{name}_dispatch.c", "the compile-time dispatch from the VM to your callbacks"),
        ("{name}_main.c", "the host control loop: ./{name} N steps the VM N times"),
        ("Makefile", "builds {name} from the sources above and the runtime"),
        ("swarmvm*", "the C VM (a copy of swarmvm's runtime): the VM and the image format it reads, Nadzoru 2's C API "
                     "(SCT_*), the trace line"),
        ("{name}_controller.c", "one {name}_on_EVENT per event and one {name}_check_EVENT per uncontrollable event"),
        ("{name}.svm", "the table image"),
        ("README.md", "this file"))))
