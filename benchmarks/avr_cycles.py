"""Cost of one VM step on the ATmega328P (simavr, 8 MHz) for every corpus supervisor, and the
VM core's flash and RAM, for the current VM and the baseline (benchmarks/baseline.py) side by
side in one run.

The conformance harness (firmware/harness/) is built as a Kilobot image would be: kilolib's
flags (-O3), the model's exact limits, the image in flash with SVM_IMAGE_SOURCES =
SVM_FLASH_ONLY and SVM_MASK_EXACT = 1; the current VM also with the generated Kilobot
Makefile's features (no runtime binding table, no learned policy; the first and weighted
policies stay, the benchmark runs them). The baseline is built from its own sources (runtime
and harness) with the same flags and batch.
Timer1 at prescaler 1 counts the CPU cycles of each ``svm_step`` (calibrated so that an empty
measurement reads 0); simavr models the AVR's cycle timing, so these are cycles. The figures
include the harness's checks and actions, called through compile-time dispatch as a generated
application's are.

Each supervisor runs one random script of STEPS steps (density 0.25) under every option
combination (inputs x control x policy); the table gives the mean and the worst step over all
of them, the mean for the default options and for edge inputs with if-quiet control (once
taken for the published Kilobot VM's behaviour: that VM is edge inputs with a choice after the
inputs on every step, in its file's event order, which the C API's exact mode reproduces,
runtime_c/README.md; its RAM on the published program is 862 B). Every trace of both VMs is compared with the Python reference, so a figure is never
that of a wrong run. Same scripts as benchmarks/m4_cycles.py.

The core's flash and RAM come from benchmarks/avr_core.c (the image loaded from flash and
stepped through a dispatch, nothing else) linked and measured by ``swarmvm footprint``: the
current VM as the generated Kilobot Makefile builds it (its features, -ffunction-sections and
--gc-sections), at kilolib's -O3 and at -Os; the baseline as its Makefile built it (-O3).

The cycles are not what ``swarmvm footprint --cycles`` measures (swarmvm.footprint.cycles, the
simavr Kilobot board), and so not its code: that runs a user's kilolib program unchanged with
one event script, its checks answered from the script, and times ``svm_step`` from outside.
This benchmark times the conformance harness, built with a timer around each step, over every
option combination of both VMs, and checks every trace against the Python reference; a kilolib
program has none of that to compare. The bytes are the same measure, and use the package's:
``swarmvm.footprint.measure.measure``."""

import argparse
import re
import statistics
import subprocess
import tempfile
from statistics import geometric_mean
from pathlib import Path

from step_costs import DEFAULT, STEPS, benchmark_batch, checked_costs, mean_of
from baseline import BASELINE, baseline_tree
from conformance import c_harness  # step_costs put tests/ on the path
from conformance.cases import OPTIONS, SUPERVISORS
from swarmvm.footprint import measure as footprint
from figures import add_json_option, write_figures

# The "edge+if-quiet" column's options (not the published Kilobot VM's: see the docstring).
KILOBOT_VM = ("edge", "if-quiet", "uniform")
FLASH_ONLY = ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"]    # as the Kilobot Makefile
# The generated Kilobot Makefile's features (templates/kilobot/Makefile.j2), with the policies the
# benchmark runs; the harness's trace reads the names.
HARNESS_FEATURES = ["-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_LEARNED=0"]
KILOBOT_FEATURES = ["-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_NAMES=0", "-DSVM_WITH_FIRST=0", "-DSVM_WITH_LEARNED=0"]
GC = ["-ffunction-sections", "-Wl,--gc-sections"]
CORE_PROGRAM = Path(__file__).resolve().parent / "avr_core.c"


def with_opt(opt):
    """kilolib's flags with another optimisation level."""
    return [opt if f.startswith("-O") else f for f in c_harness.KILOBOT_FLAGS]


def symbol_size(elf, name):
    out = subprocess.run(["avr-nm", "-S", str(elf)], capture_output=True, text=True, check=True).stdout
    match = re.search(r"^[0-9a-f]+ ([0-9a-f]+) [bBdD] %s$" % re.escape(name), out, re.M)
    return int(match.group(1), 16) if match else None


def core(batch, workdir, root, flags, extra):
    """(core flash, the VM's static RAM) of avr_core.c for the batch, built from ``root``'s
    runtime: the flash of runtime_c/*.c as `swarmvm footprint` counts it, sizeof svm_vm_t."""
    runtime, _ = c_harness.tree(root)
    out = c_harness._write_header(batch, Path(workdir))
    elf = out / "core.elf"
    weighted = ["-DSVM_WITH_WEIGHTED=%d" % (batch.image[5] & 0x02 != 0)] if root is None else []
    subprocess.run(["avr-gcc", *c_harness.WARNINGS, *flags, *FLASH_ONLY, *extra, *weighted, *c_harness.limits(batch),
                    "-I", str(out), "-I", str(runtime), str(CORE_PROGRAM), str(runtime / "swarmvm.c"), "-o", str(elf)],
                   check=True, capture_output=True, text=True)
    return footprint(elf, batch.name, "kilobot", runtime=runtime).flash.core, symbol_size(elf, "vm")


def cycles(batch, workdir, root, extra):
    """{run index: [cycles per step]} of the harness built from ``root``, checked."""
    elf, _ = c_harness.build_avr(batch, Path(workdir), cycles=True, extra=FLASH_ONLY + extra,
                                 loaded_modes=(c_harness.LOADED_NONE,), root=root)
    return checked_costs(batch, c_harness.run_avr(elf))


def summary(batch, counts):
    every = [c for steps in counts.values() for c in steps]
    return dict(mean=statistics.mean(every), worst=max(every), default=mean_of(batch, counts, DEFAULT),
                kilobot=mean_of(batch, counts, KILOBOT_VM))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_json_option(parser)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        base = baseline_tree(Path(workdir))
        for path in SUPERVISORS:
            batch = benchmark_batch(path)
            w = Path(workdir) / batch.name
            # Interleaved: the baseline and the current VM of one supervisor, then the next.
            before = summary(batch, cycles(batch, w / "base", base, []))
            after = summary(batch, cycles(batch, w / "cur", None, HARNESS_FEATURES))
            flash_before, ram_before = core(batch, w / "core-base", base, c_harness.KILOBOT_FLAGS, [])
            flash_o3, ram_after = core(batch, w / "core-O3", None, c_harness.KILOBOT_FLAGS + GC, KILOBOT_FEATURES)
            flash_os, _ = core(batch, w / "core-Os", None, with_opt("-Os") + GC, KILOBOT_FEATURES)
            rows.append(dict(name=batch.name, events=batch.image[6], supervisors=batch.image[7], image=len(batch.image),
                             baseline=before, current=after, ratio=before["mean"] / after["mean"],
                             core_flash=dict(baseline=flash_before, current_O3=flash_o3, current_Os=flash_os),
                             vm_ram=dict(baseline=ram_before, current=ram_after)))
    print("Cycles per VM step on the ATmega328P (simavr, 8 MHz, Timer1), current VM vs baseline %s; %d steps x %d "
          "option combinations; ratio = baseline / current (above 1: the current VM is faster)" %
          (BASELINE, STEPS, len(OPTIONS)))
    print("| supervisor | E | N | baseline mean | current mean | ratio | current worst | current default "
          "| current edge+if-quiet | core flash B baseline -> -O3 / -Os | VM RAM B | image B |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        b, c, f, ram = r["baseline"], r["current"], r["core_flash"], r["vm_ram"]
        print("| %s | %d | %d | %.0f | %.0f | %.2f | %d | %.0f | %.0f | %d -> %d / %d | %d -> %d | %d |"
              % (r["name"], r["events"], r["supervisors"], b["mean"], c["mean"], r["ratio"], c["worst"], c["default"],
                 c["kilobot"], f["baseline"], f["current_O3"], f["current_Os"], ram["baseline"], ram["current"],
                 r["image"]))
    ratios = [r["ratio"] for r in rows]
    print("AVR summary: cycles per step %.2fx the baseline's speed (geometric mean; %.2f-%.2f); core flash %d-%d B "
          "at -O3, %d-%d B at -Os (baseline %d-%d B); VM RAM %d-%d B"
          % (geometric_mean(ratios), min(ratios), max(ratios),
             min(r["core_flash"]["current_O3"] for r in rows), max(r["core_flash"]["current_O3"] for r in rows),
             min(r["core_flash"]["current_Os"] for r in rows), max(r["core_flash"]["current_Os"] for r in rows),
             min(r["core_flash"]["baseline"] for r in rows), max(r["core_flash"]["baseline"] for r in rows),
             min(r["vm_ram"]["current"] for r in rows), max(r["vm_ram"]["current"] for r in rows)))
    write_figures(args.json, dict(baseline=BASELINE, steps=STEPS, rows=rows))


if __name__ == "__main__":
    main()
