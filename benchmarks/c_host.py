"""The C VM on the host, current against the baseline (benchmarks/baseline.py), side by side in
one run for every corpus supervisor: image loads per second and trace steps per second.

- **load**: benchmarks/c_load.c, svm_load of the supervisor's image in RAM (length, magic,
  version, CRC-16, layout and index checks), best of ROUNDS runs (each the best of 3 timed
  rounds).
- **trace**: the host conformance harness (firmware/harness/svm_harness.c + platform_host.c,
  each version its own) running one random script of TRACE_STEPS steps under every option
  combination, in both of its passes (the image compiled in, then loaded into RAM), and
  printing every trace line (docs/conformance.md) into a pipe; steps (trace lines) per second
  of wall time, best of ROUNDS runs. The current harness's output is checked against the
  Python reference first, so the rate is that of a correct trace.

Both versions are built with the same compiler and flags (gcc -O2, the model's exact limits);
each supervisor's baseline and current programs run alternately. Run with `make bench` or
`python benchmarks/c_host.py`."""

import argparse
import subprocess
import tempfile
import time
from statistics import geometric_mean
from pathlib import Path

from step_costs import SEED, DENSITY
from baseline import BASELINE, baseline_tree
from conformance import c_harness  # step_costs put tests/ on the path
from conformance.cases import OPTIONS, SUPERVISORS, Batch, Run, reference
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.readers.event_script import random_script
from figures import add_json_option, write_figures

TRACE_STEPS = 20000
ROUNDS = 3
LOAD_PROGRAM = Path(__file__).resolve().parent / "c_load.c"


def trace_batch(path):
    """One random script of TRACE_STEPS steps, run under every option combination."""
    compiled = compile_inputs([path])
    script = tuple(frozenset(r) for r in random_script(compiled.tables, TRACE_STEPS, SEED, DENSITY))
    runs = tuple(Run(i, c, p, SEED, 0) for i, c, p in OPTIONS)
    return Batch(Path(path).stem, path, compiled.image, (script,), runs)


def load_program(batch, workdir, root):
    """benchmarks/c_load.c for the batch, built against ``root``'s runtime (None: this one)."""
    runtime, _ = c_harness.tree(root)
    out = c_harness._write_header(batch, Path(workdir))
    exe = out / "c_load"
    subprocess.run(["gcc", *c_harness.WARNINGS, "-O2", "-D_POSIX_C_SOURCE=199309L", *c_harness.limits(batch),
                    "-I", str(out), "-I", str(runtime), str(LOAD_PROGRAM), str(runtime / "swarmvm.c"), "-o", str(exe)],
                   check=True, capture_output=True, text=True)
    return exe


def load_rate(exe):
    return float(subprocess.run([str(exe), "3"], check=True, capture_output=True, text=True).stdout)


def trace_seconds(exe):
    """Wall time of one harness run, its output read from a pipe."""
    start = time.perf_counter()
    subprocess.run([str(exe)], check=True, stdout=subprocess.PIPE)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_json_option(parser)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        base = baseline_tree(Path(workdir))
        for path in SUPERVISORS:
            batch = trace_batch(path)
            w = Path(workdir) / batch.name
            versions = (("baseline", base), ("current", None))
            loaders = {name: load_program(batch, w / ("load-" + name), root) for name, root in versions}
            exes = {name: c_harness.build_host(batch, w / ("trace-" + name), root=root) for name, root in versions}
            output = c_harness.run_host(exes["current"])
            traces, _ = c_harness.parse(output)
            if any(traces.get((0, k)) != reference(batch, run) for k, run in enumerate(batch.runs)):
                raise SystemExit("%s: the current harness's trace differs from the reference" % batch.name)
            # Every trace line is a step: both passes (image compiled in, then loaded into RAM).
            steps = sum(1 for line in output.splitlines() if line and not line.startswith("@"))
            loads = {name: 0.0 for name in exes}
            best = {name: float("inf") for name in exes}
            for _ in range(ROUNDS):     # alternating, so that load on the host hits both alike
                for name in exes:
                    loads[name] = max(loads[name], load_rate(loaders[name]))
                    best[name] = min(best[name], trace_seconds(exes[name]))
            rows.append(dict(supervisor=batch.name, image=len(batch.image), loads=loads,
                             trace={name: steps / best[name] for name in best},
                             load_ratio=loads["current"] / loads["baseline"],
                             trace_ratio=best["baseline"] / best["current"]))
    print("C VM on the host (gcc -O2): image loads per second and trace steps per second, current vs the VM of %s "
          "(best of %d rounds; trace: %d steps x %d option combinations, printed into a pipe)"
          % (BASELINE, ROUNDS, TRACE_STEPS, len(OPTIONS)))
    print("| supervisor | image B | loads/s baseline | loads/s current | ratio | trace steps/s baseline "
          "| trace steps/s current | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | {:,} | {:,} | %.2f | {:,} | {:,} | %.2f |".format(
            int(r["loads"]["baseline"]), int(r["loads"]["current"]), int(r["trace"]["baseline"]),
            int(r["trace"]["current"])) % (r["supervisor"], r["image"], r["load_ratio"], r["trace_ratio"]))
    print("C host summary: image load %.2fx the baseline's rate (geometric mean; %.2f-%.2f); trace %.2fx "
          "(%.2f-%.2f), %s-%s steps per second"
          % (geometric_mean([r["load_ratio"] for r in rows]), min(r["load_ratio"] for r in rows),
             max(r["load_ratio"] for r in rows), geometric_mean([r["trace_ratio"] for r in rows]),
             min(r["trace_ratio"] for r in rows), max(r["trace_ratio"] for r in rows),
             "{:,}".format(int(min(r["trace"]["current"] for r in rows))),
             "{:,}".format(int(max(r["trace"]["current"] for r in rows)))))
    write_figures(args.json, dict(baseline=BASELINE, trace_steps=TRACE_STEPS, rows=rows))


if __name__ == "__main__":
    main()
