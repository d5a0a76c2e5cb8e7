"""Event names of any allowed length (up to 255 characters) print whole in the C trace, as in
the Python reference (the C printer used to cut them at 47 characters)."""

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import Batch, Run, one_supervisor_yaml
from swarmvm.compiler.pipeline import compile_inputs

LONG = "x" * 255
MODEL = one_supervisor_yaml([LONG, "u"], [1, 0], [LONG, "u"])


def test_a_255_character_name_prints_whole(tmp_path):
    model = tmp_path / "long_names.yaml"
    model.write_text(MODEL)
    compiled = compile_inputs([str(model)])
    u = compiled.model.events.index("u")
    b = Batch("long_names", str(model), compiled.image, (tuple(frozenset({u} if k % 2 else ()) for k in range(6)),),
              (Run("level", "after-inputs", "uniform", 1, 0),))
    traces, info = c_harness.parse(c_harness.run_host(c_harness.build_host(b, tmp_path)))
    assert "EV_" + LONG in traces[(0, 0)][0]
    assert mismatches(b, traces, info, passes=(0, 1)) == []
