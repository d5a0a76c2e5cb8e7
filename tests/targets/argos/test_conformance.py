"""Conformance in real ARGoS: several e-pucks run the generated controller, each replaying the
same `swarmvm script` rows in place of its checks (<report script=...>) and printing its trace
(<report trace="true">); every robot's trace equals `swarmvm trace` for that script, the
options, and the robot's VM seed: the experiment's random_seed XOR FNV-1a of the robot id.
The swarm's traces, one per robot, also make an inspector page (docs/inspect.md) whose every
step holds the states each robot's trace gives."""

import pytest
from targets.argos.argos_project import experiment, reference_trace, robot_lines, robot_seed, run_argos, write_script

from conformance.inspected import inspected_states, states_of

pytestmark = [pytest.mark.emulator, pytest.mark.slow]

ROBOTS = 4
STEPS = 60          # 6 s at the generated file's 10 ticks per second
RANDOM_SEED = 7
OPTIONS = ({"inputs": "level", "control": "after-inputs", "policy": "uniform"},
           {"inputs": "edge", "control": "if-quiet", "policy": "first"})


@pytest.mark.parametrize("options", OPTIONS, ids=lambda o: "-".join(o.values()))
@pytest.mark.parametrize("built", ["energy_worker", "network_worker"])
def test_every_robot_traces_the_reference(request, built, options, tmp_path):
    project, _ = request.getfixturevalue(built)
    script = write_script(project, STEPS, seed=3)
    status, log, err = run_argos(project, experiment(
        project, "conformance", robots=ROBOTS, length=STEPS // 10, random_seed=RANDOM_SEED, options=options,
        report={"trace": "true", "script": script.name}))
    assert status == 0, err
    traces = robot_lines(log, "trace")
    assert sorted(traces) == ["ep%d" % i for i in range(ROBOTS)]
    expected = {robot: reference_trace(project, script, robot_seed(RANDOM_SEED, robot), options, robot)
                for robot in traces}
    if built == "network_worker" and options["policy"] == "uniform":   # its choices depend on the seed
        assert len(set(map(tuple, expected.values()))) == ROBOTS
    for robot, lines in traces.items():
        assert len(lines) == STEPS
        assert lines == expected[robot], robot
    assert inspected_states(project.supervisor, traces, tmp_path) == states_of(traces)



def test_script_naming_a_controllable_event_stops_the_experiment(energy_worker):
    project, _ = energy_worker
    (project.folder / "bad_events.txt").write_text("-\nEV_moveToWork\n")
    status, _, err = run_argos(project, experiment(project, "bad_script", report={"script": "bad_events.txt"}))
    assert status != 0
    assert "event script line 2: EV_moveToWork is controllable" in err
