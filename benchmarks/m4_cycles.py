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
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from conformance import c_harness, qemu_harness  # noqa: E402
from conformance.cases import OPTIONS, SUPERVISORS, Batch, Run, reference  # noqa: E402
from swarmvm.pipeline import compile_inputs  # noqa: E402
from swarmvm.script import random_script  # noqa: E402

STEPS = 200
SEED = 7
DENSITY = 0.25
DEFAULT = ("level", "after-inputs", "uniform")


def benchmark_batch(path):
    compiled = compile_inputs([path])
    script = tuple(frozenset(r) for r in random_script(compiled.tables, STEPS, SEED, DENSITY))
    runs = tuple(Run(i, c, p, SEED, 0) for i, c, p in OPTIONS)
    return Batch(Path(path).stem, path, compiled.image, (script,), runs)


def measure(batch, workdir):
    """{run index: [instructions per step]} for the flash pass, checked against the reference."""
    elf = qemu_harness.build_qemu(batch, Path(workdir) / batch.name, cycles=True)
    status, output = qemu_harness.run_qemu(elf, icount=True)
    traces, info = c_harness.parse(output)
    if status != 0 or not info["end"]:
        raise SystemExit("%s: harness failed in QEMU (exit status %d)" % (batch.name, status))
    for number, run in enumerate(batch.runs):
        if traces.get((0, number)) != reference(batch, run):
            raise SystemExit("%s: run %d differs from the reference trace" % (batch.name, number))
    counts = {}
    for (pass_, run), instructions in info["cycles"]:
        if pass_ == 0:
            counts.setdefault(run, []).append(instructions)
    return counts


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
            default = counts[batch.runs.index(Run(*DEFAULT, SEED, 0))]
            rows.append(dict(supervisor=batch.name, steps=len(every), mean=sum(every) / len(every),
                             worst=max(every), mean_default=sum(default) / len(default)))
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
