"""What the per-step cost benchmarks (avr_cycles.py, m4_cycles.py) share: the random script
every supervisor runs under every option combination, and the rule that a figure only counts
when its run printed exactly the Python reference trace."""

import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from conformance import c_harness  # noqa: E402
from conformance.cases import OPTIONS, Batch, Run, reference  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm.readers.event_script import random_script  # noqa: E402

STEPS = 200
SEED = 7
DENSITY = 0.25
DEFAULT = ("level", "after-inputs", "uniform")


def benchmark_batch(path):
    """One random script of STEPS steps, run under every option combination."""
    compiled = compile_inputs([path])
    script = tuple(frozenset(r) for r in random_script(compiled.tables, STEPS, SEED, DENSITY))
    runs = tuple(Run(i, c, p, SEED, 0) for i, c, p in OPTIONS)
    return Batch(Path(path).stem, path, compiled.image, (script,), runs)


def checked_costs(batch, output):
    """{run index: [cost per step]} from a harness's output (first pass, image compiled in),
    after checking every run's trace against the reference."""
    traces, info = c_harness.parse(output)
    if not info["end"] or info["error"] is not None:
        raise SystemExit("%s: the harness did not finish" % batch.name)
    for number, run in enumerate(batch.runs):
        if traces.get((0, number)) != reference(batch, run):
            raise SystemExit("%s: run %d differs from the reference trace" % (batch.name, number))
    costs = {}
    for (pass_, run), cost in info["cycles"]:
        if pass_ == 0:
            costs.setdefault(run, []).append(cost)
    return costs


def mean_of(batch, costs, options):
    """Mean cost per step over the runs of one option combination (inputs, control, policy)."""
    return statistics.mean(c for k, run in enumerate(batch.runs)
                           if (run.inputs, run.control, run.policy) == options for c in costs[k])
