"""The CapBot target (templates/capbot/, docs/robots/capbot.md): a Zephyr application for the
nRF52840, and how footprint reads the bare-metal Cortex-M4F image the project links from it
(mk/capbot.mk) and runs in QEMU."""

from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import TEMPLATES
from .c import file_order
from .record import Elf, Readme, Target
from .values import C_RUNTIME_GROUPS, c_copies, features, sources

# What the indirect calls of a CapBot image built from the generated sources reach
# (docs/footprint.md, "Stack"), written into the project's sidecar (CapBot images come from more
# than one build, so these are the statement of the builds of gen's project, not of every ARM
# image): the dispatch and violation hook the generated Zephyr main.c gives
# the VM, and in the bare-metal QEMU build of the same sources (firmware/capbot/app_qemu.c, the
# main that replaces it) its dispatch, the character sinks it gives the trace printer, and newlib's
# stdio writing a stream (its FILE's write and seek functions). Zephyr's own (thread entry,
# logging backends, interrupt handlers) are the kernel's: a Zephyr image's bound stays unknown
# past them until they are declared.
CAPBOT_INDIRECT = ("svm_step=dispatch,on_violation,traced_dispatch", "svm_put_decimal=to_stdout,to_stderr",
                   "__sfvwrite_r=__swrite", "__sflush_r=__swrite,__sseek")


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
    # the first Cortex-M target: every ARM image no other target claims (by a symbol) is the CapBot's;
    # its sidecar's script has 20 steps, as many as the bare-metal QEMU build runs (SVM_APP_STEPS of
    # firmware/capbot/app_qemu.c)
    elf=Elf("EM_ARM", architecture="arm", emulator="qemu_m4", make_rule="{build}/capbot/{name}.elf",
            generated_indirect=CAPBOT_INDIRECT, script_steps=20),
    readme=Readme("capbot/readme.md.j2", (
        ("CMakeLists.txt", "the Zephyr application: its sources, the VM's limits for this model, the control-logic "
                           "flash page's address; copies {name}.footprint.json beside the zephyr.elf it builds"),
        ("prj.conf", "Zephyr's configuration of the application"),
        ("learned.conf", "the Kconfig options -DSVM_LEARNED=ON adds (flash map, page layout)"),
        ("src/main.c", "boot (the logic from the flash page, or compiled in), the 100 ms step loop, log output"),
        ("src/{name}_tables.[ch]", "the table image as a const array, event constants"),
        ("src/{name}_dispatch.c", "the dispatch to your callbacks"),
        ("src/{name}_controller.c", "one {name}_on_EVENT per event (actions) and one {name}_check_EVENT per "
                                    "uncontrollable event (nonzero when it occurred), on the CapBot API"),
        ("src/swarmvm*", "the C VM (a copy of swarmvm's runtime): the VM, the Nadzoru-compatible C API, the "
                         "flash-page loader, the learned policy and its flash store"),
        ("{name}.svm", "the table image, for the control-logic flash page or swarmvm check"),
        ("{name}.footprint.json", "what swarmvm footprint needs to measure the image (its indirect calls, an "
                                  "event script for --cycles, the table image's digest)"),
        ("README.md", "this file"))))
