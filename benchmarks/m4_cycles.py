"""Cost of one VM step on the Cortex-M4F (QEMU mps2-an386) for every corpus supervisor, for the
current VM and the baseline (benchmarks/baseline.py) side by side in one run.

QEMU does not model the Cortex-M4's pipeline timing, so this counts *instructions*, not
cycles: QEMU runs with ``-icount shift=10`` (each instruction advances the virtual clock by
1,024 ns) and the harness reads SysTick, clocked at 25 MHz, around each ``svm_step``
(firmware/capbot/platform_qemu.c; calibrated so that an empty measurement reads 0). On a real
Cortex-M4 most instructions take one cycle but loads and taken branches take more, so the
cycle count is somewhat higher than the instruction count; the figures include the harness's
dispatch of checks and actions, as a real application's callbacks would be.

Each supervisor runs one random script of STEPS steps (density 0.25) under every option
combination (inputs x control x policy) with the image in flash; the table gives the mean and
the worst step over all of them, and the mean for the default options alone, for both VMs,
each built from its own runtime and harness with the same flags (firmware/capbot/m4.flags),
the current one with the generated CapBot application's features (FEATURES).
Every trace is also compared with the Python reference, so a figure is never that of a wrong
run.

Not what ``swarmvm footprint --cycles`` measures (swarmvm.footprint.cycles_m4), and so not its
code: that runs a user's image unchanged, one event script with the image's own options, and
counts the instructions of each ``svm_step`` by single-stepping it through QEMU's GDB stub
(about 0.2 s per step). This benchmark runs the conformance harness, built to time itself, over
every option combination of 200-step scripts (tens of thousands of steps per supervisor, twice),
which only a program reading its own timer at full speed can do in minutes; the harness also
checks every trace against the Python reference."""

import argparse
import tempfile
from pathlib import Path

import math

from step_costs import DEFAULT, DENSITY, SEED, STEPS, benchmark_batch, checked_costs, mean_of
from baseline import BASELINE, baseline_tree
from conformance import c_harness, qemu_harness  # step_costs put tests/ on the path
from conformance.cases import OPTIONS, SUPERVISORS
from figures import add_json_option, write_figures


# The generated CapBot application's features (templates/capbot/CMakeLists.txt.j2) with the
# policies the benchmark runs; the baseline had none to choose.
FEATURES = ["-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_LEARNED=0"]


def measure(batch, workdir, root=None):
    """{run index: [instructions per step]} for the flash pass, checked against the reference;
    ``root``: another version's runtime and harness (the baseline's)."""
    elf = qemu_harness.build_qemu(batch, Path(workdir), cycles=True, root=root, extra=FEATURES if root is None else (),
                                  loaded=c_harness.LOADED_DISPATCH)    # no binding table (FEATURES)
    status, output = qemu_harness.run_qemu(elf, icount=True)
    if status != 0:
        raise SystemExit("%s: harness failed in QEMU (exit status %d)" % (batch.name, status))
    return checked_costs(batch, output)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_json_option(parser)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        base = baseline_tree(Path(workdir))
        for path in SUPERVISORS:
            batch = benchmark_batch(path)
            row = dict(supervisor=batch.name)
            for name, root in (("baseline", base), ("current", None)):    # interleaved per supervisor
                counts = measure(batch, Path(workdir) / batch.name / name, root)
                every = [n for run in counts.values() for n in run]
                row[name] = dict(steps=len(every), mean=sum(every) / len(every), worst=max(every),
                                 mean_default=mean_of(batch, counts, DEFAULT))
            row["ratio"] = row["baseline"]["mean"] / row["current"]["mean"]
            rows.append(row)
    print("Instructions per VM step on the Cortex-M4F (QEMU -icount; %d-step random script, %d option combinations, "
          "image in flash), current VM vs the VM of %s; ratio = baseline / current (above 1: fewer now)\n"
          % (STEPS, len(OPTIONS), BASELINE))
    print("| supervisor | baseline mean | current mean | ratio | current worst | current mean, default options |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        b, c = r["baseline"], r["current"]
        print("| %s | %.0f | %.0f | %.2f | %d | %.0f |" % (r["supervisor"], b["mean"], c["mean"], r["ratio"], c["worst"],
                                                          c["mean_default"]))
    ratios = [r["ratio"] for r in rows]
    print("M4 summary: %.2fx fewer instructions per step than the baseline (geometric mean; %.2f-%.2f)"
          % (math.exp(sum(math.log(x) for x in ratios) / len(ratios)), min(ratios), max(ratios)))
    write_figures(args.json, dict(unit="instructions (QEMU -icount shift=10)", baseline=BASELINE, steps=STEPS, seed=SEED, density=DENSITY, rows=rows))


if __name__ == "__main__":
    main()
