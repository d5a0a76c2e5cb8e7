"""The CapBot target (templates/capbot/, docs/robots/capbot.md): a Zephyr application for the
nRF52840, its bare-metal build for QEMU's Cortex-M4F (the project's qemu/ folder), its limits, and
how footprint reads the bare-metal image and runs it in QEMU."""

from importlib import resources

from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import TEMPLATES
from .c import file_order
from .record import Elf, Readme, RobotLimits, Target
from .values import C_RUNTIME_GROUPS, c_copies, features, has_public_inputs, minimal_features, sources

# The nRF52840's 1 MB of flash, of which the application may use what lies below the control-logic
# page at 0x000F3000 (firmware/capbot/mps2_an386.ld; the page and the bootloaders above it are not
# the program's), and its 256 KB of RAM. The stack static RAM must leave is the main thread's, in
# which the generated application steps the VM and runs the callbacks: CONFIG_MAIN_STACK_SIZE of
# the generated prj.conf, written from this figure. 2 KB is five times the deepest path measured of
# the bare-metal build of the same sources (main 388 B on the bundled example, docs/footprint.md,
# "Stack"), leaving Zephyr's logging call from the step loop and a controller's own locals room.
LIMITS = RobotLimits("CapBot", flash=0x000F3000, sram=0x40000, min_stack=2048)

# The bare-metal QEMU build of the generated sources (swarmvm.capbot_qemu: firmware/capbot/ in the
# checkout, package data in a wheel), copied into the project's qemu/ beside the Makefile gen
# writes there. Its compiler flags (m4.flags, a gcc response file) are written into that Makefile.
QEMU = resources.files("swarmvm.capbot_qemu")
QEMU_FILES = ("startup.c", "app_qemu.c", "capbot_qemu.c", "capbot.h", "mps2_an386.ld")
# How many steps the bare-metal main runs (SVM_APP_STEPS of app_qemu.c): the sidecar's script has
# as many, a longer one would end before its last step.
APP_STEPS = 20

# What the indirect calls of a CapBot image built from the generated sources reach
# (docs/footprint.md, "Stack"), written into the project's sidecar (CapBot images come from more
# than one build, so these are the statement of the builds of gen's project, not of every ARM
# image): the dispatch and violation hook the generated Zephyr main.c gives
# the VM, and in the bare-metal QEMU build of the same sources (qemu/app_qemu.c, the main that
# replaces it) its dispatch, the character sinks it gives the trace printer, and newlib's
# stdio writing a stream (its FILE's write and seek functions). Zephyr's own (thread entry,
# logging backends, interrupt handlers) are the kernel's: a Zephyr image's bound stays unknown
# past them until they are declared.
CAPBOT_INDIRECT = ("svm_step=dispatch,on_violation,svm_app_traced_dispatch", "svm_put_decimal=to_stdout,to_stderr",
                   "__sfvwrite_r=__swrite", "__sflush_r=__swrite,__sseek")


def values(compiled: Compiled) -> dict[str, object]:
    """The CMakeLists.txt and qemu/Makefile: the runtime they compile (the logic page's but in
    the minimal profile, more with ``SVM_LEARNED``, the store on Zephyr's flash last) and its features (main.c matches the logic page's events by
    name; the bare-metal trace prints them); prj.conf's main stack (LIMITS' min_stack); the
    bare-metal build's compiler flags and what its minimal profile leaves out for this model."""
    public_inputs = has_public_inputs(compiled.tables)
    return dict(runtime_sources=sources("core"), page_sources=sources("logic_page"), learned_sources=sources("learn"),
                store_sources=sources("store_zephyr"), features=features(compiled.tables.probs is not None, names=True),
                main_stack=LIMITS.min_stack, m4_flags=QEMU.joinpath("m4.flags").read_text(),
                public_inputs=public_inputs, minimal_features=minimal_features(public_inputs), app_steps=APP_STEPS,
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
               ("capbot/controller.c.j2", "src/{name}_controller.c", True),
               ("capbot/qemu.mk.j2", "qemu/Makefile", False),
               ("capbot/svm_app.h.j2", "qemu/svm_app.h", False)),
    template_folder=TEMPLATES / "capbot",
    page="robots/capbot.md",
    copies=c_copies(*C_RUNTIME_GROUPS, "logic_page", "learn", "store_zephyr", folder="src/")
    + tuple((QEMU / n, "qemu/" + n) for n in QEMU_FILES),
    values=values,
    build=("make", "-s", "-C", "qemu", "{name}.elf"),     # the bare-metal QEMU image; the robot's is west's
    limits=LIMITS,
    # the first Cortex-M target: every ARM image no other target claims (by a symbol) is the CapBot's;
    # its sidecar's script has as many steps as the bare-metal QEMU build runs
    elf=Elf("EM_ARM", architecture="arm", emulator="qemu_m4", make_rule="{build}/capbot/{name}.elf",
            generated_indirect=CAPBOT_INDIRECT, script_steps=APP_STEPS),
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
        ("qemu/Makefile", "builds qemu/{name}.elf, the same application bare-metal for QEMU's Cortex-M4F "
                          "(mps2-an386), beside a copy of {name}.footprint.json; make run runs it, MINIMAL=1 builds the "
                          "minimal flash profile"),
        ("qemu/svm_app.h", "which model the bare-metal main runs: its tables header, image, load and dispatch"),
        ("qemu/*", "the bare-metal build's start-up code, linker script, CapBot API stand-ins and main (a copy of "
                   "swarmvm's): the main plays the environment, steps the VM %d times and prints the trace" % APP_STEPS),
        ("README.md", "this file"))))
