"""The violation counter counts alike on every runtime: past 65,535 (where the C runtime used to
stop, while Python and C++ counted on) the Python, C and C++ traces are still the same lines."""

import subprocess

from conformance import c_harness
from conformance.cases import Batch, Run, one_supervisor_yaml, reference
from conformance.cpp_harness import FLAGS, c_array, runs_text
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_CPP

# EV_u is in the supervisor's alphabet but possible in no state: every step it is seen is a violation.
NEVER_POSSIBLE = one_supervisor_yaml(["c", "u"], [1, 0], ["c"])
STEPS = 70000


def test_past_65535_violations_every_runtime_agrees(tmp_path):
    model = tmp_path / "never.yaml"
    model.write_text(NEVER_POSSIBLE)
    compiled = compile_inputs([str(model)])
    u = compiled.model.events.index("u")
    b = Batch("never", str(model), compiled.image, (tuple(frozenset({u}) for _ in range(STEPS)),),
              (Run("level", "after-inputs", "uniform", 1, 0),))
    expected = reference(b, b.runs[0])
    assert expected[-1] == "%d EV_u,EV_c 0 %d" % (STEPS, STEPS)

    exe = c_harness.build_host(b, tmp_path / "c")
    traces, _ = c_harness.parse(c_harness.run_host(exe))
    assert traces[(0, 0)][-1] == expected[-1]

    (tmp_path / "images.inc").write_text(c_array("kImage0", b.image) + "const unsigned char* const kImages[] = "
                                         "{kImage0};\nconst std::size_t kImageSizes[] = {sizeof kImage0};\n")
    (tmp_path / "0.runs").write_text(runs_text(b))
    cpp = tmp_path / "harness"
    subprocess.run(["g++", *FLAGS, "-I", str(RUNTIME_CPP), "-I", str(tmp_path), '-DSWARMVM_IMAGES="images.inc"',
                    "-o", str(cpp), str(RUNTIME_CPP / "conformance_harness.cpp")], check=True)
    out = subprocess.run([str(cpp), "--compiled", "0", str(tmp_path / "0.runs")], capture_output=True, text=True,
                         check=True).stdout
    assert out.splitlines()[-2:] == [expected[-1], "end"]
