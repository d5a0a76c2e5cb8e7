"""Cost of one VM step on the ATmega328P (simavr, 8 MHz) for every corpus supervisor.

The conformance harness (firmware/harness/) is built as a Kilobot image would be: official
flags, the model's exact limits, the image in flash with SVM_IMAGE_SOURCES = SVM_FLASH_ONLY and
SVM_MASK_EXACT = 1.
Timer1 at prescaler 1 counts the CPU cycles of each ``svm_step`` (calibrated so that an empty
measurement reads 0); simavr models the AVR's cycle timing, so these are cycles. The figures
include the harness's checks and actions, called through compile-time dispatch as a generated
application's are.

Each supervisor runs one random script of STEPS steps (density 0.25) under every option
combination (inputs x control x policy); the table gives the mean and the worst step over all
of them, the mean for the default options and for the published Kilobot VM's behaviour (edge,
if-quiet), the VM's static RAM (sizeof svm_vm_t, from the symbol table), the VM core's flash
and the table image's size. Every trace is also compared with the Python reference, so a
figure is never that of a wrong run. Same scripts as benchmarks/m4_cycles.py."""

import argparse
import json
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

from step_costs import DEFAULT, STEPS, benchmark_batch, checked_costs, mean_of
from conformance import c_harness  # step_costs put tests/ on the path
from conformance.cases import OPTIONS, SUPERVISORS
from swarmvm.runtime import RUNTIME_C

KILOBOT_VM = ("edge", "if-quiet", "uniform")
FLASH_ONLY = ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"]    # as the Kilobot Makefile


def symbol_size(elf, name):
    out = subprocess.run(["avr-nm", "-S", str(elf)], capture_output=True, text=True, check=True).stdout
    match = re.search(r"^[0-9a-f]+ ([0-9a-f]+) [bBdD] %s$" % re.escape(name), out, re.M)
    return int(match.group(1), 16) if match else None


def core_flash(batch, workdir):
    """Flash of runtime_c/swarmvm.c alone, built as in a Kilobot image (text + data)."""
    obj = Path(workdir) / ("%s_core.o" % batch.name)
    subprocess.run(["avr-gcc", *c_harness.KILOBOT_FLAGS, *FLASH_ONLY, *c_harness.limits(batch), "-c",
                    str(RUNTIME_C / "swarmvm.c"), "-o", str(obj)], check=True)
    out = subprocess.run(["avr-size", str(obj)], capture_output=True, text=True, check=True).stdout
    text, data = out.splitlines()[1].split()[:2]
    return int(text) + int(data)


def measure(batch, workdir):
    """{run index: [cycles per step]}, checked against the reference, and the VM's RAM."""
    elf, _ = c_harness.build_avr(batch, Path(workdir) / batch.name, cycles=True, extra=FLASH_ONLY,
                                 loaded_modes=(c_harness.LOADED_NONE,))
    return checked_costs(batch, c_harness.run_avr(elf)), symbol_size(elf, "vm")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        for path in SUPERVISORS:
            batch = benchmark_batch(path)
            counts, ram = measure(batch, workdir)
            every = [c for steps in counts.values() for c in steps]
            rows.append(dict(name=batch.name, mean=statistics.mean(every), worst=max(every),
                             default=mean_of(batch, counts, DEFAULT), kilobot=mean_of(batch, counts, KILOBOT_VM),
                             vm_ram=ram, core_flash=core_flash(batch, workdir), image=len(batch.image),
                             events=batch.image[6], supervisors=batch.image[7]))
    print("Cycles per VM step on the ATmega328P (simavr, 8 MHz, Timer1); %d steps x %d option combinations"
          % (STEPS, len(OPTIONS)))
    print("| supervisor | E | N | mean | worst | mean default | mean edge+if-quiet | us/step (mean) "
          "| VM RAM B | core flash B | image B |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %d | %.0f | %d | %.0f | %.0f | %.0f | %s | %d | %d |"
              % (r["name"], r["events"], r["supervisors"], r["mean"], r["worst"], r["default"], r["kilobot"],
                 r["mean"] / 8.0, r["vm_ram"], r["core_flash"], r["image"]))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(rows, indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    main()
