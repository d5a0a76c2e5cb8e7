"""The c target (templates/c/, docs/robots/c.md): the C VM with a host control loop and a
Makefile, for a host or any microcontroller a C99 compiler builds for."""

from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import TEMPLATES
from .record import Target
from .values import C_RUNTIME_GROUPS, c_copies, headers, sources


def values(compiled: Compiled) -> dict[str, object]:
    """The Makefile: the runtime it compiles (the core and Nadzoru's C API)."""
    return dict(runtime_sources=sources("core", "sct"), runtime_headers=headers("core", "sct"))


TARGET = Target(
    "c",
    "C VM (C99, host or microcontroller): tables with the image as a const array, dispatch glue, control loop, Makefile, controller skeleton",
    templates=(("c/tables.h.j2", "{name}_tables.h", False),
               ("c/tables.c.j2", "{name}_tables.c", False),
               ("c/main.c.j2", "{name}_main.c", False),
               ("c/Makefile.j2", "Makefile", False),
               ("c/controller.c.j2", "{name}_controller.c", True)),
    template_folder=TEMPLATES / "c",
    page="robots/c.md",
    copies=c_copies(*C_RUNTIME_GROUPS),
    values=values,
    build=("make", "-s"))
