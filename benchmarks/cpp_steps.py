"""C++ VM steps per second on the host, for every corpus supervisor: the current VM against the
baseline VM (benchmarks/baseline.py: runtime_cpp/swarmvm.hpp as it was at that commit) and
against a straightforward VM in the style of the published OpenSwarm C++ VM
(benchmarks/cpp_baseline.hpp: event names in a std::map, a linear walk of a flat transition
array per lookup).

The driver (benchmarks/cpp_steps.cpp) is built twice in one run, once against each swarmvm.hpp,
with the same flags; both builds run the same event script and check their VM's states against
the straightforward VM's before timing, so every figure times the same work. The two builds run
alternately, ROUNDS times per supervisor, and each figure is the best round (the host is shared:
load spikes hit single rounds). Run with `make bench` or `python benchmarks/cpp_steps.py`.
"""

import argparse
import json
import subprocess
import sys
import tempfile
from statistics import geometric_mean
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from swarmvm.pipeline import compile_inputs  # noqa: E402
from baseline import BASELINE, baseline_tree  # noqa: E402

CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
FLAGS = ["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]
ROUNDS = 3


def build(compiler, runtime, exe):
    """The driver against the swarmvm.hpp in ``runtime``."""
    subprocess.run([compiler] + FLAGS + ["-I", str(runtime), "-o", str(exe), str(ROOT / "benchmarks" / "cpp_steps.cpp")],
                   check=True)
    return exe


def rates(exe, steps, image):
    """(swarmvm steps/s, straightforward VM steps/s) of one run of a driver on one image."""
    out = subprocess.run([str(exe), str(steps), str(image)], check=True, capture_output=True, text=True).stdout
    _, fast, slow = out.split()
    return float(fast), float(slow)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100000, help="steps per timed round of the driver")
    parser.add_argument("--compiler", default="g++")
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        current = build(args.compiler, ROOT / "runtime_cpp", tmp / "cpp_steps")
        baseline = build(args.compiler, baseline_tree(tmp, ("runtime_cpp",)) / "runtime_cpp", tmp / "cpp_steps_baseline")
        for path in CORPUS:
            compiled = compile_inputs([str(path)])
            image = tmp / (path.stem + ".svm")
            image.write_bytes(compiled.image)
            now = before = flat = 0.0
            for _ in range(ROUNDS):
                fast, slow = rates(current, args.steps, image)
                now, flat = max(now, fast), max(flat, slow)
                before = max(before, rates(baseline, args.steps, image)[0])
            rows.append(dict(supervisor=path.stem, events=compiled.tables.num_events,
                             supervisors=compiled.tables.num_supervisors, states=compiled.tables.num_states,
                             current=now, baseline=before, straightforward=flat, ratio=now / before,
                             ratio_straightforward=now / flat))
    print("C++ VM steps per second (%s -O2, best of %d alternating rounds of %d steps): current VM vs the VM of %s "
          "and vs a straightforward VM (map of names + linear walk)" % (args.compiler, ROUNDS, args.steps, BASELINE))
    print("| supervisor | events | supervisors | states | current steps/s | baseline steps/s | ratio "
          "| straightforward steps/s | ratio |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %d | %d | %s | %s | %.2f | %s | %.2f |" % (
            r["supervisor"], r["events"], r["supervisors"], r["states"], "{:,}".format(int(r["current"])),
            "{:,}".format(int(r["baseline"])), r["ratio"], "{:,}".format(int(r["straightforward"])),
            r["ratio_straightforward"]))
    ratios = [r["ratio"] for r in rows]
    print("C++ summary: %.2fx the baseline's steps per second (geometric mean; %.2f-%.2f), %.2fx the "
          "straightforward VM's" % (geometric_mean(ratios), min(ratios), max(ratios),
                                    geometric_mean([r["ratio_straightforward"] for r in rows])))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(dict(baseline=BASELINE, steps=args.steps, rows=rows), indent=1) + "\n")


if __name__ == "__main__":
    main()
