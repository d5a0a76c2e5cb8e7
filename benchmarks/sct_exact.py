"""The Python SCT exact step (docs/compat.md) against the same step at main 7f1712f (issue 24).

Each VM runs in its own process from a folder holding its swarmvm_vm.py and swarmvm_format.py:
the current runtime_py/ and the two files as they were at 7f1712f (``git show``). Both run
``SCT(path)`` in exact mode on the same supervisor with the same checks (each true on a fixed
pattern of steps) and the same global ``random`` seed, on every corpus supervisor; the table
prints exact steps per second, best of three, and the ratio (issue 24 asks for at least 1.4x on
uav, where it was slowest, and no supervisor slower)."""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from figures import add_json_option, write_figures

ROOT = Path(__file__).resolve().parent.parent
BASELINE = "7f1712f"
FILES = ("swarmvm_vm.py", "swarmvm_format.py")
STEPS = 20000
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))

# Run in the child: steps per second of the exact step, best of three.
CHILD = """
import random, sys, time
from swarmvm_vm import SCT
path, steps = sys.argv[1], int(sys.argv[2])
best = 0.0
for _ in range(3):
    sct = SCT(path)
    tick = [0]
    for name, index in sct.EV.items():
        if not sct.ev_controllable[index]:
            sct.add_callback(index, None, lambda _d, i=index: (tick[0] * 7 + i * 3) % 5 < 2, None)
    random.seed(1)
    start = time.process_time()
    for tick[0] in range(steps):
        sct.run_step()
    best = max(best, steps / (time.process_time() - start))
print(best)
"""


def rate(folder, path, steps):
    """Exact steps per second of the VM in ``folder`` on ``path``."""
    out = subprocess.run([sys.executable, "-c", CHILD, path, str(steps)], check=True, capture_output=True, text=True,
                         env={"PYTHONPATH": "%s:%s" % (folder, ROOT / "generator"), "PATH": "/usr/bin:/bin"})
    return float(out.stdout)


def baseline_folder(into):
    """The VM files as they were at BASELINE, written into ``into``."""
    for name in FILES:
        text = subprocess.run(["git", "-C", str(ROOT), "show", "%s:runtime_py/%s" % (BASELINE, name)], check=True,
                              capture_output=True, text=True).stdout
        (Path(into) / name).write_text(text)
    return into


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_json_option(parser)
    parser.add_argument("--steps", type=int, default=STEPS)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as old:
        baseline_folder(old)
        print("| supervisor | exact steps/s now | at %s | ratio |" % BASELINE)
        print("|---|---|---|---|")
        for path in CORPUS:
            now, then = rate(ROOT / "runtime_py", str(path), args.steps), rate(old, str(path), args.steps)
            rows.append({"supervisor": path.stem, "now": now, "baseline": then, "ratio": now / then})
            print("| %s | %.0f | %.0f | %.2fx |" % (path.stem, now, then, now / then))
    write_figures(args.json, rows)


if __name__ == "__main__":
    main()
