"""Awkward names and faults on the ARGoS target, in real ARGoS. Event names that collided in
generated C++ (``x`` beside ``received_x``, issue 12) give a controller that builds without a
warning; a user action that throws stops the experiment with one ARGoS error naming the
controller, the robot, the event and the callback (swarmvm::CallbackError, docs/semantics.md)."""

import pytest
from targets.argos.argos_project import build, experiment, generate, run_argos
from conformance.cases import supervisor_yaml

pytestmark = [pytest.mark.emulator, pytest.mark.slow]

# x: public controllable (its message "x" is received as _x); received_x: private
# uncontrollable (callback Check_received_x, as _x's would be); stream: private controllable.
AWKWARD = supervisor_yaml(["x", "received_x", "stream"], [1, 0, 1], [{"x", "received_x", "stream"}],
                          [[[("x", 0), ("received_x", 0), ("stream", 0)]]], public=[1, 0, 0])

# The user's controller, edited: EV_stream's action throws.
THROWING_ACTION = """// EV_stream: the motor driver fails.
void CAwkwardController::On_stream() {
    throw std::runtime_error("motor stalled");
}
"""


@pytest.fixture(scope="module")
def awkward(argos_prefix, tmp_path_factory):
    folder = tmp_path_factory.mktemp("argos_awkward")
    (folder / "awkward.yaml").write_text(AWKWARD)
    project = generate(folder / "awkward.yaml", folder / "project")
    return project, build(project, "g++", "-DARGOS_PREFIX=%s" % argos_prefix)


def test_names_that_collided_build_warning_free(awkward):
    project, log = awkward
    assert (project.folder / "build" / "libawkward_controller.so").is_file()
    assert "warning" not in log.lower(), log


def test_a_throwing_action_stops_the_experiment_naming_robot_event_and_callback(awkward, argos_prefix):
    project, _ = awkward
    source = project.folder / "awkward_controller.cpp"
    text = source.read_text()
    start = text.index("// EV_stream:")
    end = text.index("REGISTER_CONTROLLER")
    source.write_text("#include <stdexcept>\n" + text[:start] + THROWING_ACTION + "\n" + text[end:])
    build(project, "g++", "-DARGOS_PREFIX=%s" % argos_prefix)
    status, _, errors = run_argos(project, experiment(project, "throwing", robots=1, length=2))
    assert status != 0
    assert "CAwkwardController on robot ep0: the action of EV_stream threw: motor stalled" in errors, errors
