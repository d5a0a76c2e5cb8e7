"""`make emulate`, second half: one event script of a supervisor replayed on every C/C++
runtime, each trace compared with the Python reference VM's, one verdict line per target.

The script is what `swarmvm script MODEL --steps N --seed S` prints and the reference what
`swarmvm trace MODEL --script FILE` prints (default options: level inputs, control after
inputs, uniform policy, seed 1). The runtimes run it through the conformance harnesses the
test suite uses (tests/conformance/): the C harness on simavr (ATmega328P, official Kilobot
flags), on QEMU mps2-an386 (Cortex-M4F) and natively, and the C++ harness natively. The
embedded harnesses run the image compiled in and, where RAM allows, loaded at run time; every
pass must match. Exit status 1 on any difference. A model too wide for the ATmega328P's 2 KB of
RAM even with its image in flash only is not run there: one line says so and names the limit."""

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from conformance import c_harness, qemu_harness  # noqa: E402
from conformance.cases import Batch, Run  # noqa: E402
from conformance.cpp_harness import FLAGS as CPP_FLAGS, runs_text  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm.compiler.runtime_files import RUNTIME_CPP  # noqa: E402
from swarmvm.readers.event_script import parse_script  # noqa: E402

PASS_NAMES = {0: "compiled in", 1: "loaded", 2: "EEPROM"}


def swarmvm(*args):
    """The command line of the swarmvm this Python runs (whether or not its venv is on PATH)."""
    return subprocess.run([sys.executable, "-m", "swarmvm", *map(str, args)], check=True, capture_output=True, text=True).stdout


def harness_passes(output):
    """{pass: trace lines} of run 0 from a C harness's output."""
    traces, _ = c_harness.parse(output)
    return {p: lines for (p, run), lines in traces.items() if run == 0}


def on_simavr(b, outdir):
    elf, _ = c_harness.build_avr(b, outdir)
    return harness_passes(c_harness.run_avr(elf))


def on_qemu(b, outdir):
    status, output = qemu_harness.run_qemu(qemu_harness.build_qemu(b, outdir))
    return harness_passes(output) if status == 0 else {}


def on_host_c(b, outdir):
    return harness_passes(c_harness.run_host(c_harness.build_host(b, outdir)))


def on_host_cpp(b, outdir):
    outdir.mkdir(parents=True, exist_ok=True)
    exe, image, runs = outdir / "conformance_harness", outdir / "image.svm", outdir / "runs.txt"
    subprocess.run(["g++", *CPP_FLAGS, "-I", str(RUNTIME_CPP), "-o", str(exe),
                    str(RUNTIME_CPP / "conformance_harness.cpp")], check=True, capture_output=True)
    image.write_bytes(b.image)
    runs.write_text(runs_text(b))
    out = subprocess.run([str(exe), "--image", str(image), str(runs)], check=True, capture_output=True, text=True)
    return {1: out.stdout.split("end\n")[0].splitlines()}


TARGETS = (
    ("simavr", "ATmega328P", on_simavr),
    ("QEMU", "Cortex-M4F", on_qemu),
    ("host C", "gcc", on_host_c),
    ("host C++", "g++", on_host_cpp),
)


def verdict(passes, expected):
    """(ok, text) for one target's traces per pass against the reference lines."""
    if not passes:
        return False, "no trace (build or run failed)"
    for p, lines in sorted(passes.items()):
        if lines != expected:
            step = next((i for i, (a, b) in enumerate(zip(lines, expected)) if a != b), min(len(lines), len(expected)))
            got = lines[step] if step < len(lines) else "(end)"
            want = expected[step] if step < len(expected) else "(end)"
            return False, "DIFFERS (%s image) at step %d: %r, Python VM %r" % (PASS_NAMES[p], step + 1, got, want)
    return True, "identical to the Python VM (%s)" % ", ".join(PASS_NAMES[p] + " image" for p in sorted(passes))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model")
    parser.add_argument("--name", default=None)
    parser.add_argument("--steps", type=int, default=40)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--build", type=Path, default=ROOT / "build" / "emulate")
    args = parser.parse_args()

    compiled = compile_inputs([args.model], args.name)
    args.build.mkdir(parents=True, exist_ok=True)
    script = args.build / ("%s.script" % compiled.name)
    script.write_text(swarmvm("script", args.model, "--steps", args.steps, "--seed", args.seed))
    expected = swarmvm("trace", args.model, "--script", script).splitlines()
    rows = parse_script(str(script), script.read_text(), compiled.tables.names, compiled.tables.controllable)
    b = Batch(compiled.name, args.model, compiled.image, (tuple(frozenset(r) for r in rows),),
              (Run("level", "after-inputs", "uniform", 1, 0),))
    print("%s: %d-step script (swarmvm script --steps %d --seed %d), reference: swarmvm trace"
          % (compiled.name, len(rows), args.steps, args.seed))
    failed = 0
    for label, machine, run in TARGETS:
        started = time.monotonic()
        try:
            ok, text = verdict(run(b, args.build / label.replace(" ", "_").replace("+", "p")), expected)
        except c_harness.AvrRamError as error:
            ok, text = True, "not run: %s" % error
        except (subprocess.CalledProcessError, subprocess.TimeoutExpired) as error:
            ok, text = False, "FAILED: %s" % error
        failed += not ok
        print("%-9s %-11s %3d steps  %s  [%.1f s]" % (label, machine, len(expected), text, time.monotonic() - started))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
