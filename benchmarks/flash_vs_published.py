"""swarmvm's minimal profile beside the published VM (Nadzoru's generic C VM), per corpus
supervisor and per toolchain: flash, RAM and, on the ATmega328P, cycles per step, with the
three ratios swarmvm / published (issue 35, point 4).

Why a benchmark of its own: the footprint report (`make footprint`) measures swarmvm's images as
its targets build them; this compares the smallest VM a compiled-in program can have with the
VM a team would otherwise take, built side by side from the same supervisor with the same
compiler and flags, so that the ratio says which of the two is smaller and by how much.

Each side is a program of its own: the VM, its tables, and a small main that loads the tables
and steps, calling the same trivial checks and actions.

- published: benchmarks/published_form/published_vm.c with the supervisor's tables in the
  published form (benchmarks/published_form/tables.py), the events in the file's order; its
  draw from the application's generator (``-DSCT_RANDOM=app_random``, as the Kilobot program
  draws from kilolib's ``rand_soft``), so no C library generator is counted on its side;
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
is the VM's). Cycles per step: simavr's ATmega328P at 8 MHz, Timer1 at prescaler 1 read around
each step (calibrated so that an empty measurement reads 0), STEPS steps of one random script
(density 0.25, the uncontrollable events given by name, so both VMs see the same inputs),
callbacks included; mean and worst. The Cortex-M4's are not measured here (QEMU counts
instructions, not cycles: benchmarks/m4_cycles.py).

Fails closed: a missing compiler or simulator, a build that fails, an output that cannot be
read or a step too long for the 16-bit timer ends the run with status 1 and the reason."""

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

import tables as published_tables  # noqa: E402  (benchmarks/published_form/tables.py)
from conformance import c_harness  # noqa: E402
from figures import add_json_option, write_figures  # noqa: E402
from swarmvm.api import compile_model  # noqa: E402
from swarmvm.readers.event_script import random_script  # noqa: E402
from swarmvm.targets.values import has_public_inputs  # noqa: E402

RUNTIME = ROOT / "runtime_c"
PUBLISHED_VM = ROOT / "benchmarks" / "published_form" / "published_vm.c"
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
STEPS = 500
SEED = 7
DENSITY = 0.25
SIMAVR_TIMEOUT = 120

# Today's compiled-in Kilobot build (templates/kilobot/Makefile.j2's image settings), which checks
# the image at load: --validating builds it instead of the profile, for the figures before it.
VALIDATING = ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"]
COMMON = ["-std=c99", "-Wall", "-Wextra", "-Os", "-ffunction-sections", "-fdata-sections"]
# The features a compiled-in Kilobot program does not use, off (both swarmvm builds).
FEATURES = ["-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_NAMES=0", "-DSVM_WITH_FIRST=0", "-DSVM_WITH_WEIGHTED=0",
            "-DSVM_WITH_LEARNED=0"]
# The options the benchmark runs (the published VM's input rule), and swarmvm's minimal profile:
# the image trusted, the options fixed at build, no violation counter (the program reads none).
OPTIONS = "0x01u"   # SVM_INPUTS_EDGE | SVM_CONTROL_AFTER_INPUTS | SVM_POLICY_UNIFORM
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


# ---- the programs --------------------------------------------------------------------------

# What both programs share: the inputs of the current step by canonical event index (filled by
# the cycles harness from the script; a volatile the compiler cannot see through otherwise), the
# application's generator, the cycles harness on AVR.
APP = r"""
#include <stdint.h>
#include "bench_inputs.h"
volatile uint8_t app_sink;
volatile uint8_t app_row[BENCH_ROW_BYTES];
static uint8_t app_bit(uint8_t name) { return (uint8_t)((app_row[name >> 3] >> (name & 7u)) & 1u); }
#ifdef BENCH_CYCLES
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>
static void app_put(char c) { loop_until_bit_is_set(UCSR0A, UDRE0); UDR0 = (uint8_t)c; }
static void app_hex(uint32_t v)
{
    uint8_t i;
    for (i = 0; i < 8u; i++, v <<= 4) {
        app_put("0123456789abcdef"[(uint8_t)(v >> 28)]);
    }
    app_put(' ');
}
static void app_run(void)
{
    uint32_t total = 0, worst = 0;
    uint16_t step, overhead, t;
    uint8_t i, overflow = 0;
    UBRR0H = 0; UBRR0L = 0; UCSR0A = (uint8_t)(1u << U2X0); UCSR0B = (uint8_t)(1u << TXEN0);
    UCSR0C = (uint8_t)((1u << UCSZ01) | (1u << UCSZ00));
    TCCR1A = 0; TCCR1B = (uint8_t)(1u << CS10);
    TCNT1 = 0; overhead = TCNT1;
    for (step = 0; step < BENCH_STEPS; step++) {
        for (i = 0; i < BENCH_ROW_BYTES; i++) {
            app_row[i] = pgm_read_byte(&app_rows[step][i]);
        }
        TIFR1 = (uint8_t)(1u << TOV1);
        TCNT1 = 0;
        BENCH_STEP();
        t = (uint16_t)(TCNT1 - overhead);
        overflow |= (uint8_t)(TIFR1 & (1u << TOV1));
        total += t;
        if (t > worst) worst = t;
    }
    app_put('c'); app_put(' ');
    app_hex(total); app_hex(worst); app_hex(BENCH_STEPS); app_hex(overflow);
    app_put('\n');
    loop_until_bit_is_set(UCSR0A, TXC0);
    cli(); sleep_enable(); sleep_cpu();
}
#else
static void app_run(void) { for (;;) { BENCH_STEP(); } }
#endif
"""

PUBLISHED_MAIN = r"""
#include "model.h"
#define BENCH_STEP() SCT_run_step()
""" + APP + r"""
static uint8_t app_state = 1;
uint8_t app_random(void)
{   /* the application's generator (kilolib's rand_soft on a Kilobot): a byte of xorshift */
    app_state ^= (uint8_t)(app_state << 3); app_state ^= (uint8_t)(app_state >> 5);
    app_state ^= (uint8_t)(app_state << 1);
    return app_state;
}
static unsigned char app_check(void *data) { return app_bit(app_name_of[(uint8_t)(uintptr_t)data]); }
static void app_act(void *data) { app_sink = (uint8_t)(uintptr_t)data; }
int main(void)
{
    uint8_t e;
    SCT_init();
    for (e = 0; e < NUM_EVENTS; e++) {
        SCT_add_callback(e, app_act, app_check, (void *)(uintptr_t)e);
    }
    app_run();
    return 0;
}
"""

SWARMVM_MAIN = r"""
#include "swarmvm.h"
extern const uint8_t bench_image[];   /* bench_tables.c (swarmvm.h declares it in the profile) */
static svm_vm_t vm;
#define BENCH_STEP() (void)svm_step(&vm)
""" + APP + r"""
static uint8_t app_dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    if (op == SVM_OP_CHECK) {
        return app_bit(event);
    }
    app_sink = event;
    return 0;
}
int main(void)
{
    svm_init(&vm);
    svm_set_dispatch(&vm, app_dispatch);
    svm_set_options(&vm, BENCH_OPTIONS, 1u);
    if (svm_load_P(&vm, bench_image, BENCH_IMAGE_SIZE) != SVM_OK) {
        return 1;
    }
    app_run();
    return 0;
}
"""

EMPTY = "int main(void) { for (;;) { } }\n"


def c_bytes(data: bytes) -> str:
    return ",".join(str(b) for b in data)


def inputs_header(names_of: list[int], rows: list[set[int]], row_bytes: int, avr_cycles: bool) -> str:
    """bench_inputs.h: each event's canonical index (the program's own numbering -> name) and
    the script's rows as canonical masks (cycles builds only)."""
    text = ["#include <stdint.h>", "#define BENCH_ROW_BYTES %d" % row_bytes, "#define BENCH_STEPS %d" % len(rows),
            "static const uint8_t app_name_of[] = {%s};" % c_bytes(bytes(names_of))]
    if avr_cycles:
        masks = [sum(1 << e for e in row).to_bytes(row_bytes, "little") for row in rows]
        text.append("#include <avr/pgmspace.h>")
        text.append("static const uint8_t app_rows[%d][%d] PROGMEM = {%s};"
                    % (len(rows), row_bytes, ",".join("{%s}" % c_bytes(m) for m in masks)))
    return "\n".join(text) + "\n"


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
    source.write_text(EMPTY)
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
    published_cycles: Optional[float]
    swarmvm_cycles: Optional[float]
    published_worst: Optional[int]
    swarmvm_worst: Optional[int]
    swarmvm_image: int
    # swarmvm's generator (svm_random), counted in swarmvm_flash; the published program's is the
    # application's and is not counted in published_flash.
    swarmvm_generator: int = 0
    # The published program does not link for the ATmega328P (its .data and .bss over the 2 KB
    # of SRAM): it cannot run on a Kilobot, so it has no cycles; its bytes were measured with room.
    published_overflows: bool = False

    @property
    def swarmvm_flash_without_generator(self) -> int:
        return self.swarmvm_flash - self.swarmvm_generator

    def ratio(self, what: str) -> Optional[float]:
        a, b = getattr(self, "swarmvm_" + what), getattr(self, "published_" + what)
        return None if a is None or b is None else a / b


class Supervisor:
    """One supervisor's sources for both VMs, written under ``work``."""

    def __init__(self, path: Path, work: Path, profile: list[str]) -> None:
        self.profile = profile
        self.name = path.stem
        self.compiled = compile_model([str(path)], names=False)
        tables = self.compiled.tables
        self.image = self.compiled.image
        self.row_bytes = (tables.num_events + 7) // 8
        self.rows = [set(r) for r in random_script(tables, STEPS, SEED, DENSITY)]
        canonical = {name: i for i, name in enumerate(tables.names)}
        self.published_dir, self.swarmvm_dir = work / self.name / "published", work / self.name / "swarmvm"
        published_tables.write(path, self.published_dir)
        doc = published_tables.nadzoru_c_form.read_yaml(path)
        self.published_names = [canonical[e[3:] if e.startswith("EV_") else e] for e in doc["events"]]
        self.swarmvm_dir.mkdir(parents=True, exist_ok=True)
        (self.swarmvm_dir / "bench_tables.c").write_text(
            '#include "swarmvm.h"\nconst uint8_t bench_image[%d] SVM_PROGMEM = {%s};\n' % (len(self.image), c_bytes(self.image)))
        (self.published_dir / "main.c").write_text(PUBLISHED_MAIN)
        (self.swarmvm_dir / "main.c").write_text(SWARMVM_MAIN)
        self.overflows: set[tuple[str, str]] = set()
        if "-DSVM_TRUSTED_IMAGE=bench_image" in profile and not has_public_inputs(tables):
            self.profile = [*profile, NO_PUBLIC]
        self.limits = ["-DBENCH_OPTIONS=" + OPTIONS, "-DSVM_MAX_EVENTS=%d" % tables.num_events, "-DSVM_MAX_SUPERVISORS=%d" % tables.num_supervisors,
                       "-DSVM_MAX_STATES=%d" % tables.num_states, "-DBENCH_IMAGE_SIZE=%du" % len(self.image)]

    def build(self, tc: Toolchain, side: str, cycles: bool) -> Path:
        folder = self.published_dir if side == "published" else self.swarmvm_dir
        names = self.published_names if side == "published" else list(range(len(self.compiled.tables.names)))
        (folder / "bench_inputs.h").write_text(inputs_header(names, self.rows, self.row_bytes, cycles))
        elf = folder / ("%s%s.elf" % (tc.name, "_cycles" if cycles else ""))
        extra = ["-DBENCH_CYCLES"] if cycles else []
        if side == "published":
            cmd = [tc.cc, *tc.flags, *extra, "-I", str(folder), "-DSCT_TABLES=\"model_tables.c\"",
                   "-DSCT_RANDOM=app_random", "-DSCT_RANDOM_TYPE=uint8_t", "-include", "stdint.h",
                   str(folder / "main.c"), str(PUBLISHED_VM)]
        else:
            cmd = [tc.cc, *tc.flags, "-Werror", "-pedantic", *extra, *self.profile, *self.limits, "-I", str(folder),
                   "-I", str(RUNTIME), str(folder / "main.c"), str(folder / "bench_tables.c"), str(RUNTIME / "swarmvm.c")]
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


def cycles_of(elf: Path) -> tuple[float, int]:
    """(mean, worst) cycles per step of a cycles build in simavr."""
    try:
        proc = subprocess.run(["simavr", "-m", "atmega328p", "-f", "8000000", str(elf)],
                              capture_output=True, text=True, timeout=SIMAVR_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise Unmeasurable("%s: simavr did not finish in %d s" % (elf, SIMAVR_TIMEOUT))
    text = c_harness.simavr_output(proc.stderr) + proc.stdout
    match = re.search(r"c ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8}) ([0-9a-f]{8})", text)
    if match is None:
        raise Unmeasurable("%s: no cycle counts in simavr's output: %r" % (elf, text[-500:]))
    total, worst, steps, overflow = (int(g, 16) for g in match.groups())
    if overflow or steps != STEPS:
        raise Unmeasurable("%s: a step overflowed the 16-bit timer, or the run was cut short" % elf)
    return total / steps, worst


def bench(paths: list[Path], toolchains: list[Toolchain], work: Path, cycles: bool = True,
          validating: bool = False) -> list[Row]:
    """One row per supervisor and toolchain; ``validating``: swarmvm as today's Kilobot build
    (the image checked at load) instead of the minimal profile."""
    profile = [*VALIDATING, *FEATURES] if validating else PROFILE
    for tc in toolchains:
        require(tc.cc, tc.size, tc.nm)
    if cycles and any(tc.name == "avr" for tc in toolchains):
        require("simavr")
    empties = {tc.name: empty_program(tc, work) for tc in toolchains}
    rows = []
    for path in paths:
        sup = Supervisor(path, work, profile)
        for tc in toolchains:
            sizes: dict[str, Sizes] = {}
            counts: dict[str, tuple[Optional[float], Optional[int]]] = {}
            generator = 0
            for side in ("published", "swarmvm"):
                elf = sup.build(tc, side, cycles=False)
                sizes[side] = measure(tc, elf, empties[tc.name])
                if side == "swarmvm":
                    generator = symbol_bytes(tc, elf, GENERATOR)
                counts[side] = (None, None)
                if cycles and tc.name == "avr" and (tc.name, side) not in sup.overflows:
                    counts[side] = cycles_of(sup.build(tc, side, cycles=True))
            if (tc.name, "swarmvm") in sup.overflows:
                raise Unmeasurable("%s: swarmvm's program does not fit the ATmega328P's SRAM" % sup.name)
            rows.append(Row(sup.name, tc.name, sizes["published"].flash, sizes["swarmvm"].flash,
                            sizes["published"].ram, sizes["swarmvm"].ram, counts["published"][0], counts["swarmvm"][0],
                            counts["published"][1], counts["swarmvm"][1], len(sup.image),
                            generator, (tc.name, "published") in sup.overflows))
    return rows


def fmt(value: Optional[float], digits: int = 0) -> str:
    return "-" if value is None else ("{:,.%df}" % digits).format(value)


def table(rows: list[Row]) -> str:
    lines = ["| toolchain | supervisor | flash published / swarmvm (ratio) "
             "| flash swarmvm without its generator (ratio) | RAM published / swarmvm (ratio) "
             "| cycles/step mean published / swarmvm (ratio) | worst published / swarmvm |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        pub_cycles = "does not fit SRAM" if r.published_overflows else fmt(r.published_cycles)
        lines.append("| %s | %s | %s / %s (%s) | %s (%s) | %s%s / %s (%s) | %s / %s (%s) | %s / %s |" % (
            r.toolchain, r.supervisor, fmt(r.published_flash), fmt(r.swarmvm_flash), fmt(r.ratio("flash"), 2),
            fmt(r.swarmvm_flash_without_generator), fmt(r.swarmvm_flash_without_generator / r.published_flash, 2),
            fmt(r.published_ram), " (over 2,048)" if r.published_overflows else "", fmt(r.swarmvm_ram),
            fmt(r.ratio("ram"), 2), pub_cycles, fmt(r.swarmvm_cycles), fmt(r.ratio("cycles"), 2),
            fmt(r.published_worst), fmt(r.swarmvm_worst)))
    return "\n".join(lines)


def main(argv: Optional[list[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("supervisors", nargs="*", help="supervisor.yaml files (default: the corpus)")
    parser.add_argument("--toolchain", choices=("avr", "arm"), action="append", help="default: both")
    parser.add_argument("--no-cycles", action="store_true", help="flash and RAM only")
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
          + " (flash: text + data; RAM: "
          "data + bss; cycles: simavr, %d steps, edge inputs); ratio swarmvm / published" % STEPS)
    print("generators: swarmvm's flash counts its xorshift32 (%s); the published VM's counts none (it draws "
          "from the application's generator, as from rand_soft on a Kilobot); 'without its generator' takes "
          "%s's bytes off swarmvm's" % (GENERATOR, GENERATOR))
    print(table(rows))
    worse = [r for r in rows if r.swarmvm_flash >= r.published_flash]
    worse_without = [r for r in rows if r.swarmvm_flash_without_generator >= r.published_flash]
    write_figures(args.json, [dict(asdict(r), flash_ratio=r.ratio("flash"), ram_ratio=r.ratio("ram"),
                                   cycles_ratio=r.ratio("cycles"),
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
    return 1 if worse and args.check else 0


if __name__ == "__main__":
    sys.exit(main())
