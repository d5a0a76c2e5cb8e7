"""Building blocks of the C++ conformance harness (runtime_cpp/conformance_harness.cpp), shared
by its test (test_cpp.py) and by `make emulate` (firmware/emulate_example.py)."""

import subprocess
from pathlib import Path

from swarmvm.compiler.runtime_files import RUNTIME_CPP

FLAGS = ["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def build_program(source: Path, exe: Path, *extra: str) -> Path:
    """``source``, a test program of the C++ runtime, built with g++ and the project's flags."""
    subprocess.run(["g++", *FLAGS, *extra, "-I", str(RUNTIME_CPP), str(source), "-o", str(exe)], check=True,
                   capture_output=True)
    return exe


def c_array(name, data):
    """Bytes as a C++ array definition, for images compiled into the harness."""
    body = ",".join("0x%02x" % b for b in data)
    return "const unsigned char %s[] = {%s};\n" % (name, body)


def runs_text(batch):
    """The harness's RUNS file for one batch (format in conformance_harness.cpp)."""
    lines = ["scripts %d" % len(batch.scripts)]
    for script in batch.scripts:
        lines.append("script %d" % len(script))
        lines.extend(" ".join(str(e) for e in sorted(row)) or "-" for row in script)
    lines.append("runs %d" % len(batch.runs))
    lines.extend("%s %s %s %d %d" % (r.inputs, r.control, r.policy, r.seed, r.script) for r in batch.runs)
    return "\n".join(lines) + "\n"
