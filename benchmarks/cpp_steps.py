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

Then the exact mode of the drop-in for the OpenSwarm controllers (runtime_cpp/sct.h) against
the published sct.cpp it replaces (../shared/reference/openswarm-sct-cpp, built with yaml-cpp
against real ARGoS): one driver (benchmarks/cpp_sct_steps.cpp, events registered as the
published controllers do) built against each, the same flags and seed; both builds must report
the same states before their figures count. On the two supervisors where the drop-in stays below
4x, the same driver is also built against a floor (benchmarks/cpp_sct_floor.h: the supervisor
written by hand, only the callbacks and ARGoS draws the published step makes): its ratio is the
most any VM can reach there in this driver. Skipped, saying why, without ARGoS, yaml-cpp or the
published source.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from statistics import geometric_mean
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from swarmvm import api  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from baseline import BASELINE, baseline_tree  # noqa: E402
import yaml  # noqa: E402
from figures import add_json_option, write_figures  # noqa: E402

CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
FLAGS = ["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]
ROUNDS = 3
PUBLISHED = ROOT.parent / "shared" / "reference" / "openswarm-sct-cpp"
SCT_DRIVER = ROOT / "benchmarks" / "cpp_sct_steps.cpp"
# Supervisors with a hand-written floor in benchmarks/cpp_sct_floor.h: name -> its define.
SCT_FLOORS = {"public_example": "SWARMVM_FLOOR_PUBLIC_EXAMPLE",
              "probabilistic_example": "SWARMVM_FLOOR_PROBABILISTIC_EXAMPLE"}


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


def sct_prerequisites():
    """(ARGoS prefix, None), or (None, why the exact-mode comparison cannot run)."""
    if not (PUBLISHED / "sct.cpp").is_file():
        return None, "the published sct.cpp is not in %s" % PUBLISHED
    if shutil.which("pkg-config") is None or subprocess.run(["pkg-config", "--exists", "yaml-cpp"]).returncode != 0:
        return None, "yaml-cpp is not installed (libyaml-cpp-dev)"
    found = subprocess.run([str(ROOT / "scripts" / "argos.sh")], capture_output=True, text=True)
    if found.returncode != 0:
        return None, "no ARGoS (scripts/argos.sh: %s)" % (found.stderr.strip().splitlines() or ["exit %d" % found.returncode])[-1]
    return Path(found.stdout.strip()), None


def sct_rows(compiler, steps, tmp):
    """Per corpus supervisor: the drop-in's and the published VM's exact steps per second."""
    argos, why = sct_prerequisites()
    if argos is None:
        print("C++ exact mode vs the published sct.cpp: skipped, %s" % why)
        return []
    common = [compiler, "-std=c++17", "-O2", "-I%s" % (argos / "include")]
    libs = ["-L%s" % (argos / "lib" / "argos3"), "-largos3core_simulator"]
    published, dropin = tmp / "sct_published", tmp / "sct_swarmvm"
    subprocess.run([*common, "-w", "-I%s" % PUBLISHED, str(SCT_DRIVER), str(PUBLISHED / "sct.cpp"), "-o", str(published),
                    *libs, "-lyaml-cpp"], check=True)
    subprocess.run([*common, *FLAGS[1:], "-I%s" % (ROOT / "runtime_cpp"), str(SCT_DRIVER), "-o", str(dropin), *libs],
                   check=True)
    floor_header = tmp / "floor" / "sct.h"   # the driver includes "sct.h"
    floor_header.parent.mkdir()
    floor_header.write_text('#include "%s"\n' % (ROOT / "benchmarks" / "cpp_sct_floor.h"))
    floors = {}
    for name, define in SCT_FLOORS.items():
        floors[name] = tmp / ("sct_floor_" + name)
        subprocess.run([*common, *FLAGS[1:], "-D" + define, "-I%s" % floor_header.parent, "-I%s" % (ROOT / "runtime_cpp"),
                        str(SCT_DRIVER), "-o", str(floors[name]), *libs], check=True)
    env = dict(os.environ, LD_LIBRARY_PATH=str(argos / "lib" / "argos3"))
    rows = []
    for path in CORPUS:
        folder = tmp / "sct" / path.stem
        folder.mkdir(parents=True)
        supervisor = folder / "supervisor.yaml"
        shutil.copy(path, supervisor)
        api.write_image([str(supervisor)], str(folder / "supervisor.svm"))
        kinds = "".join(str(k) for k in yaml.safe_load(path.read_text())["ev_controllable"])
        best = {}
        exes = (published, dropin) + ((floors[path.stem],) if path.stem in floors else ())
        for _ in range(ROUNDS):
            for exe in exes:
                out = subprocess.run([str(exe), str(steps), str(supervisor), kinds], check=True, capture_output=True,
                                     text=True, env=env).stdout
                _, checksum, rate = next(line for line in out.splitlines() if line.startswith(str(supervisor))).split()
                best.setdefault(exe, []).append((checksum, float(rate)))
        if len({checksum for runs in best.values() for checksum, _ in runs}) != 1:
            raise SystemExit("%s: the published VM, the drop-in and the floor disagree" % path.stem)
        now, then = (max(rate for _, rate in best[exe]) for exe in (dropin, published))
        rows.append(dict(supervisor=path.stem, dropin=now, published=then, ratio=now / then))
        if path.stem in floors:
            rows[-1]["floor_ratio"] = max(rate for _, rate in best[floors[path.stem]]) / then
    print("C++ exact mode: the drop-in SCT (runtime_cpp/sct.h) vs the published sct.cpp, steps per second "
          "(%s -O2, ARGoS's generator, best of %d alternating rounds of %d steps)" % (compiler, ROUNDS, steps))
    print("| supervisor | drop-in steps/s | published steps/s | ratio | floor's ratio (the most any VM reaches) |")
    print("|---|---|---|---|---|")
    for r in rows:
        floor = "%.2f" % r["floor_ratio"] if "floor_ratio" in r else ""
        print("| %s | {:,} | {:,} | %.2f | %s |".format(int(r["dropin"]), int(r["published"]))
              % (r["supervisor"], r["ratio"], floor))
    ratios = [r["ratio"] for r in rows]
    print("C++ exact summary: %.2fx the published sct.cpp's steps per second (geometric mean; %.2f-%.2f)"
          % (geometric_mean(ratios), min(ratios), max(ratios)))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100000, help="steps per timed round of the driver")
    parser.add_argument("--compiler", default="g++")
    add_json_option(parser)
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
    with tempfile.TemporaryDirectory() as tmp:
        exact = sct_rows(args.compiler, args.steps, Path(tmp))
    write_figures(args.json, dict(baseline=BASELINE, steps=args.steps, rows=rows, exact=exact))


if __name__ == "__main__":
    main()
