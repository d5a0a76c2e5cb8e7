"""A throwaway target (tests/targets/test_throwaway_target.py): a host "robot" whose program steps
the VM ten times. It is what docs/extending.md says a target is, and nothing more: this module,
its template folder (../templates/toy/) and its docs page (../docs/toy.md), found through
SWARMVM_TARGET_PATH. It reuses the c target's tables and controller templates, has one naming rule
of its own, limits small enough that its image exceeds them, and ELF files told apart by a symbol."""

from pathlib import Path

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.pipeline import Compiled
from swarmvm.targets.record import Elf, RobotLimits, Target
from swarmvm.targets.values import C_RUNTIME_GROUPS, c_copies, headers, sources

HERE = Path(__file__).resolve().parent.parent
FLASH = 1000        # bytes: less than any host program, so the footprint check fails


def rules(compiled: Compiled) -> dict[str, object]:
    """The toy's own naming rule: it keeps the event names starting with ``toy`` for itself."""
    for name in compiled.model.events:
        if name.startswith("toy"):
            raise InputError(compiled.model.source, "events", "the toy keeps names starting with 'toy'",
                             "event EV_%s" % name)
    return {}


def values(compiled: Compiled) -> dict[str, object]:
    """What its Makefile compiles: the VM core."""
    return dict(runtime_sources=sources("core"), runtime_headers=headers("core"))


TARGET = Target(
    "toy",
    "A throwaway host robot: tables, controller skeleton, a main stepping the VM ten times, Makefile",
    templates=(("c/tables.h.j2", "{name}_tables.h", False),
               ("c/tables.c.j2", "{name}_tables.c", False),
               ("c/dispatch.c.j2", "{name}_dispatch.c", False),
               ("c/controller.c.j2", "{name}_controller.c", True),
               ("toy/main.c.j2", "{name}_main.c", False),
               ("toy/Makefile.j2", "Makefile", False)),
    template_folder=HERE / "templates" / "toy",
    page=str(HERE / "docs" / "toy.md"),
    copies=c_copies(*C_RUNTIME_GROUPS),
    rules=rules, values=values,
    build=("make", "-s", "{name}.elf"),
    limits=RobotLimits("Toy", flash=FLASH, sram=1 << 20, min_stack=0),
    elf=Elf("EM_X86_64", symbols=("toy_board_start",)))
