"""swarmvm's minimal profile beside the published VM (Nadzoru's generic C VM), per corpus
supervisor and per toolchain: flash, RAM and the cost of a step (cycles on the ATmega328P,
instructions on the Cortex-M4F), with the three ratios swarmvm / published (issue 35, point 4).

Why a benchmark of its own: the footprint report (`make footprint`) measures swarmvm's images as
its targets build them; this compares the smallest VM a compiled-in program can have with the
VM a team would otherwise take, built side by side from the same supervisor with the same
compiler and flags, so that the ratio says which of the two is smaller and by how much.

Each side is a program of its own (benchmarks/published_form/side_by_side.py): the VM, its
tables, and a small main that loads the tables and steps, calling the same trivial checks and
actions.

- published: benchmarks/published_form/published_vm.c with the supervisor's tables in the
  published form (benchmarks/published_form/tables.py), its events numbered in swarmvm's input
  order (below); its draw from the application's generator (``-DSCT_RANDOM=app_random``, as
  the Kilobot program draws from kilolib's ``rand_soft``), so no C library generator is counted
  on its side;
- swarmvm: runtime_c/swarmvm.c in its minimal profile (``SVM_TRUSTED_IMAGE``, every
  ``SVM_WITH_*`` feature 0 -- the violation counter too, and the public-first pass when the model
  has no public uncontrollable event --, the model's exact limits, the options fixed at build with
  ``SVM_TRUSTED_OPTIONS``) with the canonical image compiled in without names (``swarmvm pack
  --no-names``'s image: the profile reads no name), run with the published VM's input rule
  (edge inputs, after-inputs, uniform).

The generators are not counted alike: the published VM's is the application's (``app_random``,
not counted), swarmvm's xorshift32 (``svm_random``) is part of the VM. The table gives both
ways: swarmvm with its generator, and without it (``svm_random``'s bytes, from ``nm -S``,
taken off), each against the published VM without its generator.

Flash is text + data of the linked ELF (``avr-size`` / ``arm-none-eabi-size``, Berkeley
format) minus that of an empty program (``main`` looping) built with the same flags, minus the
sizes of the application's own symbols (``main`` and every ``app_*`` symbol, from ``nm -S``):
what remains is the VM's code, its tables and whatever of the C library, libgcc and start-up
code they pull in. RAM is data + bss counted the same way (the swarmvm VM instance, ``vm``,
is the VM's).

The cost of a step: both programs step over one random script of STEPS steps (density 0.25,
the uncontrollable events given by name, so both VMs see the same inputs), each step timed,
callbacks included; mean and worst, timed by the conformance harness's platform files, linked
as they are, as benchmarks/avr_cycles.py and benchmarks/m4_cycles.py time their steps. On the
ATmega328P, cycles: simavr at 8 MHz, Timer1 at prescaler 1 (firmware/harness/platform_avr.c);
a published program whose tables do not fit the 328P's 2 KB of SRAM (it cannot run on a
Kilobot) is timed on the ATmega1284P, whose core takes the same cycles per instruction
(ROOMY_MCU), and its row says so.
On the Cortex-M4F, instructions, not cycles: QEMU (mps2-an386) does not model the M4's timing,
so it runs with ``-icount`` and SysTick counts instructions (firmware/capbot/platform_qemu.c,
built and run by tests/conformance/qemu_harness.py). Both VMs take the same transitions, and the run checks it: the Python
reference VM runs the script first (benchmarks/published_form/same_steps.py); the published
side's generator replays where among the enabled events swarmvm's generator chose, and its
events are numbered in swarmvm's input order, so that it applies simultaneous inputs in the
same order; each program prints the number of events it fired and their digest, and a run
whose figures differ from the other VM's or from the reference's fails.

Fails closed: a missing compiler or simulator, a build that fails, an output that cannot be
read, a step too long for the 16-bit timer or two VMs that did not take the same transitions
end the run with status 1 and the reason."""

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Optional

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks" / "published_form"))
sys.path.insert(0, str(ROOT / "benchmarks"))

import nadzoru_c_form  # noqa: E402  (tests/nadzoru_c_form.py: the published form's reader of a supervisor.yaml)
import same_steps  # noqa: E402  (benchmarks/published_form/same_steps.py)
import side_by_side  # noqa: E402  (benchmarks/published_form/side_by_side.py)
import tables as published_tables  # noqa: E402  (benchmarks/published_form/tables.py)
from conformance import c_harness, qemu_harness  # noqa: E402
from figures import add_json_option, write_figures  # noqa: E402
from swarmvm.api import compile_model  # noqa: E402
from swarmvm.readers.event_script import random_script  # noqa: E402
from swarmvm.targets.values import has_public_inputs  # noqa: E402

RUNTIME = ROOT / "runtime_c"
PUBLISHED_VM = ROOT / "benchmarks" / "published_form" / "published_vm.c"
# The step timers (and output) of the conformance harness, which benchmarks/avr_cycles.py and
# benchmarks/m4_cycles.py read, and their header.
PLATFORM_AVR = ROOT / "firmware" / "harness" / "platform_avr.c"
PLATFORM_QEMU = ROOT / "firmware" / "capbot" / "platform_qemu.c"
HARNESS = ROOT / "firmware" / "harness"
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
STEPS = 500
SEED = 7
DENSITY = 0.25
SIMAVR_TIMEOUT = 120
# The Kilobot's MCU, and where a published program that does not fit its 2 KB of SRAM is timed:
# the ATmega1284P (16 KB of SRAM) has the same AVR core and, with a 16-bit program counter as
# the 328P's, the same cycles per instruction (CALL and RET 4, RCALL and ICALL 3, LD/ST/LDS 2,
# LPM 3); simavr models both. Its flash and RAM figures stay the 328P build's.
KILOBOT_MCU = "atmega328p"
ROOMY_MCU = "atmega1284p"
# The published VM's input rule, which both VMs run (the reference's names and swarmvm's bits:
# SVM_INPUTS_EDGE | SVM_CONTROL_AFTER_INPUTS | SVM_POLICY_UNIFORM), and swarmvm's seed.
RULE = ("edge", "after-inputs", "uniform")
OPTIONS = "0x01u"
VM_SEED = 1
UNITS = {"avr": "cycles", "arm": "instructions"}

# Today's compiled-in Kilobot build (templates/kilobot/Makefile.j2's image settings), which checks
# the image at load: --validating builds it instead of the profile, for the figures before it.
VALIDATING = ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"]
COMMON = ["-std=c99", "-Wall", "-Wextra", "-Os", "-ffunction-sections", "-fdata-sections"]
# The features a compiled-in Kilobot program does not use, off (both swarmvm builds).
FEATURES = ["-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_NAMES=0", "-DSVM_WITH_FIRST=0", "-DSVM_WITH_WEIGHTED=0",
            "-DSVM_WITH_LEARNED=0"]
# swarmvm's minimal profile: the image trusted, the options fixed at build, no violation counter
# (the program reads none).
PROFILE = ["-DSVM_TRUSTED_IMAGE=bench_image", *FEATURES, "-DSVM_WITH_VIOLATIONS=0",
           "-DSVM_TRUSTED_OPTIONS=" + OPTIONS]
# Added to the profile for a model without public uncontrollable events: the step has no
# public-first pass.
NO_PUBLIC = "-DSVM_WITH_PUBLIC=0"
# swarmvm's generator, counted in its flash; the "without" figures take its bytes off.
GENERATOR = "svm_random"


class Unmeasurable(Exception):
    """A figure that cannot be measured: the run stops and says why."""


@dataclass(frozen=True)
class Toolchain:
    name: str
    cc: str
    size: str
    nm: str
    flags: tuple[str, ...]
    link: tuple[str, ...]


def avr() -> Toolchain:
    """avr-gcc for the Kilobot's ATmega328P: kilolib's flags at -Os."""
    flags = [f for f in c_harness.KILOBOT_FLAGS if not f.startswith(("-O", "-std", "-W", "-g"))]
    return Toolchain("avr", "avr-gcc", "avr-size", "avr-nm", tuple(flags + COMMON), ("-Wl,--gc-sections",))


def arm() -> Toolchain:
    """arm-none-eabi-gcc for the CapBot's Cortex-M4F, hard float, as firmware/capbot/m4.flags."""
    cpu = (ROOT / "firmware" / "capbot" / "m4.flags").read_text().split("\n")[0].split()
    return Toolchain("arm", "arm-none-eabi-gcc", "arm-none-eabi-size", "arm-none-eabi-nm", tuple(cpu + COMMON),
                     ("--specs=nosys.specs", "-Wl,--gc-sections"))


def require(*tools: str) -> None:
    missing = [t for t in tools if shutil.which(t) is None]
    if missing:
        raise Unmeasurable("not on the PATH: %s (make setup installs them)" % ", ".join(missing))


@dataclass(frozen=True)
class Sizes:
    flash: int
    ram: int


def run(cmd: list[str], what: str) -> str:
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        raise Unmeasurable("%s: %s failed: %s" % (what, cmd[0], (result.stderr or result.stdout).strip()[:2000]))
    return result.stdout


def sections(tc: Toolchain, elf: Path) -> tuple[int, int, int]:
    """(text, data, bss) of a linked ELF, Berkeley format."""
    out = run([tc.size, "-B", str(elf)], str(elf))
    match = re.search(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s", out.splitlines()[-1])
    if match is None:
        raise Unmeasurable("%s: cannot read %s's output: %r" % (elf, tc.size, out))
    return int(match.group(1)), int(match.group(2)), int(match.group(3))


def application_bytes(tc: Toolchain, elf: Path) -> Sizes:
    """The bytes of main and of every app_* symbol: flash (code, constants, .data's initial
    values) and RAM (.data, .bss)."""
    flash = ram = 0
    for line in run([tc.nm, "-S", str(elf)], str(elf)).splitlines():
        parts = line.split()
        if len(parts) != 4 or not (parts[3] == "main" or parts[3].startswith("app_")):
            continue
        size, kind = int(parts[1], 16), parts[2].lower()
        if kind in "trd":
            flash += size
        if kind in "bdv":
            ram += size
    return Sizes(flash, ram)


def symbol_bytes(tc: Toolchain, elf: Path, name: str) -> int:
    """The size of one symbol of a linked ELF (0 if it has none: e.g. inlined)."""
    for line in run([tc.nm, "-S", str(elf)], str(elf)).splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[3] == name:
            return int(parts[1], 16)
    return 0


def measure(tc: Toolchain, elf: Path, empty: Sizes) -> Sizes:
    """The VM's flash and RAM in a linked program: the program's minus the empty program's minus
    the application's own symbols."""
    text, data, bss = sections(tc, elf)
    app = application_bytes(tc, elf)
    flash, ram = text + data - empty.flash - app.flash, data + bss - empty.ram - app.ram
    if flash <= 0 or ram < 0:
        raise Unmeasurable("%s: the VM's figures come out as flash %d, RAM %d" % (elf, flash, ram))
    return Sizes(flash, ram)


def empty_program(tc: Toolchain, work: Path) -> Sizes:
    source, elf = work / "empty.c", work / ("empty_%s.elf" % tc.name)
    source.write_text(side_by_side.EMPTY)
    run([tc.cc, *tc.flags, str(source), *tc.link, "-o", str(elf)], "empty program")
    text, data, bss = sections(tc, elf)
    return Sizes(text + data, data + bss)


@dataclass
class Row:
    supervisor: str
    toolchain: str
    published_flash: int
    swarmvm_flash: int
    published_ram: int
    swarmvm_ram: int
    # The cost of a step (step_unit: cycles on avr, instructions on arm), mean and worst.
    published_step: Optional[float]
    swarmvm_step: Optional[float]
    published_worst: Optional[int]
    swarmvm_worst: Optional[int]
    swarmvm_image: int
    step_unit: str
    # The events the VMs fired over the script and their digest (the same on both sides and the
    # reference's: checked), None where nothing was stepped.
    fired: Optional[int] = None
    digest: Optional[int] = None
    # swarmvm's generator (svm_random), counted in swarmvm_flash; the published program's is the
    # application's and is not counted in published_flash.
    swarmvm_generator: int = 0
    # The published program does not link for the ATmega328P (its .data and .bss over the 2 KB
    # of SRAM): it cannot run on a Kilobot; its bytes were measured with room, its cycles on the
    # ATmega1284P (ROOMY_MCU).
    published_overflows: bool = False

    @property
    def swarmvm_flash_without_generator(self) -> int:
        return self.swarmvm_flash - self.swarmvm_generator

    def ratio(self, what: str) -> Optional[float]:
        a, b = getattr(self, "swarmvm_" + what), getattr(self, "published_" + what)
        return None if a is None or b is None else a / b


@dataclass(frozen=True)
class Steps:
    """One program's run over the script: the cost of its steps and what it fired."""
    mean: float
    worst: int
    fired: int
    digest: int


class Supervisor:
    """One supervisor's sources for both VMs, written under ``work``."""

    def __init__(self, path: Path, work: Path, profile: list[str]) -> None:
        self.profile = profile
        self.name = path.stem
        self.compiled = compile_model([str(path)], names=False)
        tables = self.compiled.tables
        self.image = self.compiled.image
        self.rows = [set(r) for r in random_script(tables, STEPS, SEED, DENSITY)]
        self.expected = same_steps.expected(self.image, self.rows, *RULE, seed=VM_SEED)
        controllable = [e for e in range(tables.num_events) if tables.controllable >> e & 1]
        # The published tables numbered in swarmvm's input order: published index -> canonical.
        self.published_names = same_steps.published_order(self.expected.input_order, controllable)
        self.published_dir, self.swarmvm_dir = work / self.name / "published", work / self.name / "swarmvm"
        doc_name = {(e[3:] if e.startswith("EV_") else e): e
                    for e in nadzoru_c_form.read_yaml(path)["events"]}
        published_tables.write(path, self.published_dir,
                               order=[doc_name[tables.names[e]] for e in self.published_names])
        self.swarmvm_dir.mkdir(parents=True, exist_ok=True)
        (self.swarmvm_dir / "bench_tables.c").write_text(
            '#include "swarmvm.h"\nconst uint8_t bench_image[%d] SVM_PROGMEM = {%s};\n'
            % (len(self.image), side_by_side.c_bytes(self.image)))
        (self.published_dir / "main.c").write_text(side_by_side.PUBLISHED_MAIN)
        (self.swarmvm_dir / "main.c").write_text(side_by_side.SWARMVM_MAIN)
        self.overflows: set[tuple[str, str]] = set()
        if "-DSVM_TRUSTED_IMAGE=bench_image" in profile and not has_public_inputs(tables):
            self.profile = [*profile, NO_PUBLIC]
        self.limits = ["-DBENCH_OPTIONS=" + OPTIONS, "-DBENCH_SEED=%du" % VM_SEED,
                       "-DSVM_MAX_EVENTS=%d" % tables.num_events, "-DSVM_MAX_SUPERVISORS=%d" % tables.num_supervisors,
                       "-DSVM_MAX_STATES=%d" % tables.num_states, "-DBENCH_IMAGE_SIZE=%du" % len(self.image)]

    def sources(self, side: str, platform: Optional[Path]) -> tuple[Path, list[str], list[Path]]:
        """(folder, compiler flags, sources) of one side's program, its inputs header written;
        ``platform``: the cycles build's, with the harness platform that times the steps."""
        folder = self.published_dir if side == "published" else self.swarmvm_dir
        names = self.published_names if side == "published" else list(range(len(self.compiled.tables.names)))
        (folder / "bench_inputs.h").write_text(
            side_by_side.inputs_header(names, self.rows, self.expected.draws, platform is not None))
        timed = ([] if platform is None else
                 ["-DBENCH_CYCLES", "-DSVM_HARNESS_CYCLES", "-I", str(HARNESS), "-I", str(RUNTIME)])
        more = [] if platform is None else [platform]
        if side == "published":
            return folder, ["-I", str(folder), *timed, "-DSCT_TABLES=\"model_tables.c\"", "-DSCT_RANDOM=app_random",
                            "-DSCT_RANDOM_TYPE=uint8_t", "-include", "stdint.h"], [folder / "main.c", PUBLISHED_VM, *more]
        return folder, ["-Werror", "-pedantic", *self.profile, *self.limits, "-I", str(folder), "-I", str(RUNTIME),
                        *timed], [folder / "main.c", folder / "bench_tables.c", RUNTIME / "swarmvm.c", *more]

    def build(self, tc: Toolchain, side: str, cycles: bool, mcu: str = KILOBOT_MCU) -> Path:
        """One side's program for a toolchain: the flash build, or the AVR cycles build (for
        `mcu`, the Kilobot's or ROOMY_MCU)."""
        folder, flags, sources = self.sources(side, PLATFORM_AVR if cycles else None)
        elf = folder / ("%s%s%s.elf" % (tc.name, "_cycles" if cycles else "", "" if mcu == KILOBOT_MCU else "_" + mcu))
        machine = [f if f != "-mmcu=" + KILOBOT_MCU else "-mmcu=" + mcu for f in tc.flags]
        cmd = [tc.cc, *machine, *flags, *map(str, sources)]
        what = "%s/%s/%s" % (self.name, side, tc.name)
        try:
            run([*cmd, *tc.link, "-o", str(elf)], what)
        except Unmeasurable as exc:
            if tc.name != "avr" or "not within region `data'" not in str(exc):
                raise
            # The published VM keeps its tables in .data: a large model's overflow the
            # ATmega328P's 2 KB of SRAM, and the program cannot run on a Kilobot. Linked again
            # with room for them, its bytes are still measured, and the row says it does not fit.
            run([*cmd, *tc.link, "-Wl,--defsym=__DATA_REGION_LENGTH__=0x10000", "-o", str(elf)], what)
            self.overflows.add((tc.name, side))
        return elf

    def build_qemu(self, side: str) -> Path:
        """One side's instruction-count build for QEMU's mps2-an386, as benchmarks/m4_cycles.py's
        harness is built (qemu_harness.compile_m4: firmware/capbot's flags, start-up code and
        linker script), with its SysTick timer (platform_qemu.c)."""
        folder, flags, sources = self.sources(side, PLATFORM_QEMU)
        elf = folder / "arm_instructions.elf"
        try:
            return Path(qemu_harness.compile_m4(sources, elf, flags))
        except subprocess.CalledProcessError as exc:
            raise Unmeasurable("%s/%s/arm (QEMU): arm-none-eabi-gcc failed: %s"
                               % (self.name, side, (exc.stderr or "").strip()[:2000]))

    def steps(self, tc: Toolchain, side: str) -> Steps:
        """One side's run over the script on the toolchain's simulator (simavr, QEMU); on AVR a
        program that does not fit the ATmega328P's SRAM on the ATmega1284P (ROOMY_MCU)."""
        if tc.name == "avr":
            mcu = ROOMY_MCU if (tc.name, side) in self.overflows else KILOBOT_MCU
            elf = self.build(tc, side, cycles=True, mcu=mcu)
            return parse_steps(elf, simavr_output(elf, mcu))
        elf = self.build_qemu(side)
        return parse_steps(elf, qemu_output(elf))


def parse_steps(elf: Path, text: str) -> Steps:
    """The figures of a cycles build's line (benchmarks/published_form/side_by_side.py)."""
    match = re.search(r"c ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8})", text)
    if match is None:
        raise Unmeasurable("%s: no step counts in the simulator's output: %r" % (elf, text[-500:]))
    total, worst, steps, overflow, fired, digest = (int(g, 16) for g in match.groups())
    if overflow or steps != STEPS:
        raise Unmeasurable("%s: a step overflowed the 16-bit timer, or the run was cut short" % elf)
    return Steps(total / steps, worst, fired, digest)


def simavr_output(elf: Path, mcu: str = KILOBOT_MCU) -> str:
    try:
        proc = subprocess.run(["simavr", "-m", mcu, "-f", "8000000", str(elf)],
                              capture_output=True, text=True, timeout=SIMAVR_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise Unmeasurable("%s: simavr did not finish in %d s" % (elf, SIMAVR_TIMEOUT))
    return str(c_harness.simavr_output(proc.stderr)) + proc.stdout


def qemu_output(elf: Path) -> str:
    status, out, err = qemu_harness.run(elf, icount=True)
    if status != 0:
        raise Unmeasurable("%s: QEMU ended with status %d: %s" % (elf, status, (err or out).strip()[-500:]))
    return str(out)


def same_transitions(sup: Supervisor, tc: Toolchain, runs: dict[str, Steps]) -> tuple[int, int]:
    """(fired, digest) of the runs, which must be the reference's, or Unmeasurable: the two VMs
    took different transitions, or both others than the reference VM."""
    want = (sup.expected.fired, sup.expected.digest)
    got = {side: (r.fired, r.digest) for side, r in runs.items()}
    if len(set(got.values())) > 1:
        raise Unmeasurable("%s/%s: the published VM and swarmvm took different transitions over the script "
                           "(published: %d events fired, digest %08x; swarmvm: %d, %08x; the reference: %d, %08x)"
                           % (sup.name, tc.name, *got["published"], *got["swarmvm"], *want))
    for side, figures in got.items():
        if figures != want:
            raise Unmeasurable("%s/%s: %s took other transitions than the reference VM (%d events fired, digest "
                               "%08x; the reference: %d, %08x)"
                               % (sup.name, tc.name, "both VMs" if len(got) == 2 else side, *figures, *want))
    return want


def bench(paths: list[Path], toolchains: list[Toolchain], work: Path, cycles: bool = True,
          validating: bool = False) -> list[Row]:
    """One row per supervisor and toolchain; ``cycles``: also the cost of a step (simavr on
    avr, QEMU on arm); ``validating``: swarmvm as today's Kilobot build (the image checked at
    load) instead of the minimal profile."""
    profile = [*VALIDATING, *FEATURES] if validating else PROFILE
    for tc in toolchains:
        require(tc.cc, tc.size, tc.nm)
    if cycles:
        require(*(("simavr",) if any(tc.name == "avr" for tc in toolchains) else ()),
                *(("qemu-system-arm",) if any(tc.name == "arm" for tc in toolchains) else ()))
    empties = {tc.name: empty_program(tc, work) for tc in toolchains}
    rows = []
    for path in paths:
        sup = Supervisor(path, work, profile)
        for tc in toolchains:
            sizes: dict[str, Sizes] = {}
            generator = 0
            for side in ("published", "swarmvm"):
                elf = sup.build(tc, side, cycles=False)
                sizes[side] = measure(tc, elf, empties[tc.name])
                if side == "swarmvm":
                    generator = symbol_bytes(tc, elf, GENERATOR)
            if (tc.name, "swarmvm") in sup.overflows:
                raise Unmeasurable("%s: swarmvm's program does not fit the ATmega328P's SRAM" % sup.name)
            runs = {side: sup.steps(tc, side) for side in ("published", "swarmvm") if cycles}
            pub, svm = runs.get("published"), runs.get("swarmvm")
            fired, digest = same_transitions(sup, tc, runs) if runs else (None, None)
            rows.append(Row(sup.name, tc.name, sizes["published"].flash, sizes["swarmvm"].flash,
                            sizes["published"].ram, sizes["swarmvm"].ram,
                            pub.mean if pub else None, svm.mean if svm else None,
                            pub.worst if pub else None, svm.worst if svm else None,
                            len(sup.image), UNITS[tc.name], fired, digest,
                            generator, (tc.name, "published") in sup.overflows))
    return rows


def fmt(value: Optional[float], digits: int = 0) -> str:
    return "-" if value is None else ("{:,.%df}" % digits).format(value)


def table(rows: list[Row]) -> str:
    lines = ["| toolchain | supervisor | flash published / swarmvm (ratio) "
             "| flash swarmvm without its generator (ratio) | RAM published / swarmvm (ratio) "
             "| per step (unit): mean published / swarmvm (ratio) | worst published / swarmvm | events fired (both) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        pub_step = fmt(r.published_step) + (" (on the %s)" % ROOMY_MCU if r.published_overflows else "")
        lines.append("| %s | %s | %s / %s (%s) | %s (%s) | %s%s / %s (%s) | (%s) %s / %s (%s) | %s / %s | %s |" % (
            r.toolchain, r.supervisor, fmt(r.published_flash), fmt(r.swarmvm_flash), fmt(r.ratio("flash"), 2),
            fmt(r.swarmvm_flash_without_generator), fmt(r.swarmvm_flash_without_generator / r.published_flash, 2),
            fmt(r.published_ram), " (over 2,048)" if r.published_overflows else "", fmt(r.swarmvm_ram),
            fmt(r.ratio("ram"), 2), r.step_unit, pub_step, fmt(r.swarmvm_step), fmt(r.ratio("step"), 2),
            fmt(r.published_worst), fmt(r.swarmvm_worst), fmt(r.fired)))
    return "\n".join(lines)


def main(argv: Optional[list[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("supervisors", nargs="*", help="supervisor.yaml files (default: the corpus)")
    parser.add_argument("--toolchain", choices=("avr", "arm"), action="append", help="default: both")
    parser.add_argument("--no-cycles", action="store_true", help="flash and RAM only (no simulator)")
    parser.add_argument("--validating", action="store_true",
                        help="swarmvm as today's compiled-in Kilobot build, which checks the image at load")
    parser.add_argument("--check", action="store_true", help="exit with status 1 where swarmvm's flash is not below")
    add_json_option(parser)
    args = parser.parse_args(argv)
    paths = [Path(p) for p in args.supervisors] or CORPUS
    toolchains = [{"avr": avr, "arm": arm}[name]() for name in (args.toolchain or ["avr", "arm"])]
    try:
        with tempfile.TemporaryDirectory(prefix="flash_vs_published_") as work:
            rows = bench(paths, toolchains, Path(work), cycles=not args.no_cycles, validating=args.validating)
    except Unmeasurable as exc:
        print("flash_vs_published: cannot measure: %s" % exc, file=sys.stderr)
        return 1
    print("swarmvm's %s vs the published VM: VM + tables, bytes" % ("validating build" if args.validating else "minimal profile")
          + " (flash: text + data; RAM: data + bss); per step: %d steps of one script, edge inputs, both VMs taking "
          "the same transitions (checked): avr cycles in simavr, arm instructions counted in QEMU -icount (QEMU does "
          "not model the Cortex-M4's timing: not cycles); ratio swarmvm / published" % STEPS)
    print("generators: swarmvm's flash counts its xorshift32 (%s); the published VM's counts none (it draws "
          "from the application's generator, as from rand_soft on a Kilobot); 'without its generator' takes "
          "%s's bytes off swarmvm's" % (GENERATOR, GENERATOR))
    print(table(rows))
    worse = [r for r in rows if r.swarmvm_flash >= r.published_flash]
    worse_without = [r for r in rows if r.swarmvm_flash_without_generator >= r.published_flash]
    write_figures(args.json, [dict(asdict(r), flash_ratio=r.ratio("flash"), ram_ratio=r.ratio("ram"),
                                   step_ratio=r.ratio("step"),
                                   swarmvm_flash_without_generator=r.swarmvm_flash_without_generator,
                                   flash_ratio_without_generator=r.swarmvm_flash_without_generator / r.published_flash)
                              for r in rows])
    # A target not met is a figure, not a failure of the run (tests/footprint/ judges it);
    # --check makes it the exit status.
    if worse:
        print("flash_vs_published: swarmvm's flash is not below the published VM's on %d of %d: %s"
              % (len(worse), len(rows), ", ".join("%s/%s" % (r.toolchain, r.supervisor) for r in worse)))
    if worse_without:
        print("flash_vs_published: without its generator, not below on %d of %d: %s"
              % (len(worse_without), len(rows),
                 ", ".join("%s/%s" % (r.toolchain, r.supervisor) for r in worse_without)))
    slower = [r for r in rows if r.swarmvm_step is not None and r.published_step is not None
              and r.swarmvm_step >= r.published_step]
    if slower:
        print("flash_vs_published: swarmvm's step costs no less than the published VM's on %d of %d: %s"
              % (len(slower), len(rows), ", ".join("%s/%s" % (r.toolchain, r.supervisor) for r in slower)))
    return 1 if worse and args.check else 0


if __name__ == "__main__":
    sys.exit(main())
