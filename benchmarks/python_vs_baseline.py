"""The Python VM against its baseline (benchmarks/baseline.py), side by side in one process:
steps per second on the same random script and image loads per second, for every corpus
supervisor. The two run interleaved, round after round, and each keeps its best round, so a
busy machine slows both alike. Prints a table of ratios (current / baseline) and a summary
line; ``--json FILE`` also writes the figures."""

import argparse
import json
import sys
import time
from pathlib import Path

from baseline import BASELINE, ROOT, baseline_python_vm
from large_model import write_large_model

sys.path.insert(0, str(ROOT / "tests"))

from conformance.cases import SUPERVISORS  # noqa: E402
from swarmvm.pipeline import compile_inputs  # noqa: E402
from swarmvm.runtime import python_vm  # noqa: E402
from swarmvm.script import random_script  # noqa: E402

STEPS = 3000
LOADS = 100
ROUNDS = 11


def steps_per_second(module, image: bytes, rows) -> float:
    """Steps per second of ``module``'s VM replaying ``rows`` (level inputs, uniform choice)."""
    vm = module.VM(image, seed=1)
    now: set = set()
    for event in vm.input_order:
        vm.bind(event, check=lambda _data, event=event: event in now)
    start = time.process_time()
    for row in rows:
        now.clear()
        now.update(row)
        vm.step()
    return len(rows) / (time.process_time() - start)


def loads_per_second(module, image: bytes) -> float:
    """Images parsed and installed in a VM per second (the CRC check included)."""
    start = time.process_time()
    for _ in range(LOADS):
        module.VM(image, seed=1)
    return LOADS / (time.process_time() - start)


def best_of_rounds(measure, current, baseline) -> tuple[float, float]:
    """The best of ROUNDS interleaved measurements of each version."""
    ours, theirs = 0.0, 0.0
    for _ in range(ROUNDS):
        ours = max(ours, measure(current))
        theirs = max(theirs, measure(baseline))
    return ours, theirs


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", help="also write the figures to this file")
    parser.add_argument("--scratch", default=str(ROOT / "build" / "bench"), help="folder for the baseline's files")
    parser.add_argument("--only", default="", help="only the supervisors whose name holds this")
    args = parser.parse_args()
    current, baseline = python_vm(), baseline_python_vm(Path(args.scratch))
    cases = [p for p in SUPERVISORS + [str(write_large_model(Path(args.scratch)))] if args.only in Path(p).stem]
    rows_out = []
    print("Python VM against the baseline (%s), best of %d interleaved rounds" % (BASELINE, ROUNDS))
    print("| supervisor | steps/s | baseline | ratio | loads/s | baseline | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for path in cases:
        compiled = compile_inputs([path])
        rows = random_script(compiled.tables, STEPS, seed=1)
        step = best_of_rounds(lambda m: steps_per_second(m, compiled.image, rows), current, baseline)
        load = best_of_rounds(lambda m: loads_per_second(m, compiled.image), current, baseline)
        name = Path(path).stem
        rows_out.append(dict(supervisor=name, steps=step[0], steps_baseline=step[1], loads=load[0],
                             loads_baseline=load[1]))
        print("| %s | %.0f | %.0f | %.2fx | %.0f | %.0f | %.2fx |"
              % (name, step[0], step[1], step[0] / step[1], load[0], load[1], load[0] / load[1]))
    step_ratios = [r["steps"] / r["steps_baseline"] for r in rows_out]
    load_ratios = [r["loads"] / r["loads_baseline"] for r in rows_out]
    print("summary: Python VM steps %.2f-%.2fx, loads %.2f-%.2fx the baseline's (%s)"
          % (min(step_ratios), max(step_ratios), min(load_ratios), max(load_ratios), BASELINE))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(dict(baseline=BASELINE, rows=rows_out), indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    main()
