"""C++ VM steps per second on the host, for every corpus supervisor, against a baseline.

The baseline (benchmarks/cpp_baseline.hpp) is a straightforward VM in the style of the
published OpenSwarm C++ VM: event names in a std::map, a linear walk of a flat transition
array per lookup. Both run the same event script and are checked to produce the same states
before timing. Run with `make bench` or `python benchmarks/cpp_steps.py [--steps N]`.
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from swarmvm.pipeline import compile_inputs  # noqa: E402

CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
FLAGS = ["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100000, help="steps per timed round (best of 5 rounds)")
    parser.add_argument("--compiler", default="g++")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        exe = tmp / "cpp_steps"
        subprocess.run([args.compiler] + FLAGS + ["-I", str(ROOT / "runtime_cpp"), "-o", str(exe),
                        str(ROOT / "benchmarks" / "cpp_steps.cpp")], check=True)
        images, sizes = [], {}
        for path in CORPUS:
            compiled = compile_inputs([str(path)])
            image = tmp / (path.stem + ".svm")
            image.write_bytes(compiled.image)
            images.append(str(image))
            sizes[path.stem] = (compiled.tables.num_events, compiled.tables.num_supervisors,
                                compiled.tables.num_states)
        out = subprocess.run([str(exe), str(args.steps)] + images, check=True, capture_output=True,
                             text=True).stdout
    print("C++ VM steps per second (%s -O2, best of 5 rounds of %d steps; baseline = map of names + linear walk)" %
          (args.compiler, args.steps))
    print("| supervisor | events | supervisors | states | swarmvm steps/s | baseline steps/s | ratio |")
    print("|---|---|---|---|---|---|---|")
    ratios = []
    for line in out.splitlines():
        image, fast, slow = line.split()
        name = Path(image).stem
        ratio = float(fast) / float(slow)
        ratios.append(ratio)
        print("| %s | %d | %d | %d | %s | %s | %.2f |" % ((name,) + sizes[name] + (
            "{:,}".format(int(fast)), "{:,}".format(int(slow)), ratio)))
    geo = 1.0
    for r in ratios:
        geo *= r
    print("geometric mean ratio: %.2f" % geo ** (1.0 / len(ratios)))


if __name__ == "__main__":
    main()
