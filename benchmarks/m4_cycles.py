"""Cost of one VM step on the Cortex-M4F (QEMU mps2-an386) for every corpus supervisor.

QEMU does not model the Cortex-M4's pipeline timing, so this counts *instructions*, not
cycles: QEMU runs with ``-icount shift=10`` (each instruction advances the virtual clock by
1,024 ns) and the harness reads SysTick, clocked at 25 MHz, around each ``svm_step``
(firmware/capbot/platform_qemu.c; calibrated so that an empty measurement reads 0). On a real
Cortex-M4 most instructions take one cycle but loads and taken branches take more, so the
cycle count is somewhat higher than the instruction count; the figures include the harness's
dispatch of checks and actions, as a real application's callbacks would be.

Each supervisor runs one random script of STEPS steps (density 0.25) under every option
combination (inputs x control x policy) with the image in flash; the table gives the mean and
the worst step over all of them, and the mean for the default options alone. Every trace is
also compared with the Python reference, so a figure is never that of a wrong run."""

import argparse
import json
import tempfile
from pathlib import Path

from step_costs import DEFAULT, DENSITY, SEED, STEPS, benchmark_batch, checked_costs, mean_of
from conformance import qemu_harness  # step_costs put tests/ on the path
from conformance.cases import OPTIONS, SUPERVISORS


def measure(batch, workdir):
    """{run index: [instructions per step]} for the flash pass, checked against the reference."""
    elf = qemu_harness.build_qemu(batch, Path(workdir) / batch.name, cycles=True)
    status, output = qemu_harness.run_qemu(elf, icount=True)
    if status != 0:
        raise SystemExit("%s: harness failed in QEMU (exit status %d)" % (batch.name, status))
    return checked_costs(batch, output)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        for path in SUPERVISORS:
            batch = benchmark_batch(path)
            counts = measure(batch, workdir)
            every = [n for run in counts.values() for n in run]
            rows.append(dict(supervisor=batch.name, steps=len(every), mean=sum(every) / len(every),
                             worst=max(every), mean_default=mean_of(batch, counts, DEFAULT)))
    print("Instructions per VM step on the Cortex-M4F (QEMU -icount; %d-step random script, "
          "%d option combinations, image in flash)\n" % (STEPS, len(OPTIONS)))
    print("| supervisor | steps | mean | worst | mean, default options |")
    print("|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %.0f | %d | %.0f |" % (r["supervisor"], r["steps"], r["mean"], r["worst"], r["mean_default"]))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(dict(unit="instructions (QEMU -icount shift=10)", steps=STEPS,
                                                   seed=SEED, density=DENSITY, rows=rows), indent=2) + "\n")


if __name__ == "__main__":
    main()
