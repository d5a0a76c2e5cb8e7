"""A model at the image format's limit of 255 events: the C harness builds without a warning
(it failed -Werror=type-limits there) and prints the Python reference's trace."""

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import Batch, Run, one_supervisor_yaml
from swarmvm.compiler.pipeline import compile_inputs

EVENTS = ["c"] + ["u%d" % i for i in range(254)]
MODEL = one_supervisor_yaml(EVENTS, [1] + [0] * 254, EVENTS)


def test_255_events_on_the_host(tmp_path):
    model = tmp_path / "widest.yaml"
    model.write_text(MODEL)
    compiled = compile_inputs([str(model)])
    every_other = frozenset(range(1, 255, 2))
    b = Batch("widest", str(model), compiled.image, ((every_other, frozenset(), every_other),),
              (Run("level", "after-inputs", "uniform", 1, 0), Run("edge", "if-quiet", "first", 7, 0)))
    traces, info = c_harness.parse(c_harness.run_host(c_harness.build_host(b, tmp_path)))
    assert len(traces[(0, 0)][0].split()[1].split(",")) == 128      # 127 inputs and the choice
    assert mismatches(b, traces, info, passes=(0, 1)) == []
