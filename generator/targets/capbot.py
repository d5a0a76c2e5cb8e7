"""The CapBot target (templates/capbot/, docs/robots/capbot.md): a Zephyr application for the
nRF52840, and how footprint reads the bare-metal Cortex-M4F image the project links from it
(mk/capbot.mk) and runs in QEMU."""

from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import TEMPLATES
from .c import file_order
from .record import Elf, Target
from .values import C_RUNTIME_GROUPS, c_copies, features, sources


def values(compiled: Compiled) -> dict[str, object]:
    """The CMakeLists.txt: the runtime it compiles (more with ``SVM_LEARNED``, the store on
    Zephyr's flash last) and its features (main.c matches the logic page's events by name)."""
    return dict(runtime_sources=sources("core", "logic_page"), learned_sources=sources("learn"),
                store_sources=sources("store_zephyr"), features=features(compiled.tables.probs is not None, names=True),
                **file_order(compiled))


TARGET = Target(
    "capbot",
    "CapBot application (Zephyr, nRF52840): CMakeLists.txt, prj.conf, main stepping the VM every 100 ms, tables, controller skeleton on the CapBot API",
    templates=(("capbot/CMakeLists.txt.j2", "CMakeLists.txt", False),
               ("capbot/prj.conf.j2", "prj.conf", False),
               ("capbot/learned.conf.j2", "learned.conf", False),
               ("capbot/main.c.j2", "src/main.c", False),
               ("c/tables.h.j2", "src/{name}_tables.h", False),
               ("c/tables.c.j2", "src/{name}_tables.c", False),
               ("c/dispatch.c.j2", "src/{name}_dispatch.c", False),
               ("capbot/controller.c.j2", "src/{name}_controller.c", True)),
    template_folder=TEMPLATES / "capbot",
    page="robots/capbot.md",
    copies=c_copies(*C_RUNTIME_GROUPS, "logic_page", "learn", "store_zephyr", folder="src/"),
    values=values,
    # the first Cortex-M target: every ARM image no other target claims (by a symbol) is the CapBot's
    elf=Elf("EM_ARM", architecture="arm", emulator="qemu_m4", make_rule="{build}/capbot/{name}.elf"))
