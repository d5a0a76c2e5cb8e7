"""The generated .argos file runs as it is in real ARGoS (six e-pucks, 300 control steps, one
summary line each), and an experiment is reproducible: with checks that read the robots'
range-and-bearing sensor, so that what happens depends on where the robots are and drive, two
runs with one random_seed write byte-identical output and another seed a different one."""

import re

import pytest
from targets.argos.argos_project import CORPUS, build, experiment, generate, robot_lines, run_argos

pytestmark = [pytest.mark.emulator, pytest.mark.slow]

SUMMARY = re.compile(r"(\d+) steps, (\d+) events fired(?: \((.*)\))?, (\d+) violations")
# A filled-in check: how many neighbours are within 60 cm, modulo 3, equals the check's number.
NEIGHBOURS = ("return std::count_if(m_pcRABSens->GetReadings().begin(), m_pcRABSens->GetReadings().end(), "
              "[](const argos::CCI_RangeAndBearingSensor::SPacket& s) { return s.Range < 60.0; }) %% 3 == %d;")


@pytest.fixture(scope="module")
def sensing_worker(argos_prefix, tmp_path_factory):
    """network_worker's controller with its private checks filled in as a user would, from the
    number of neighbours within 60 cm (range-and-bearing readings)."""
    project = generate(CORPUS / "network_worker.yaml", tmp_path_factory.mktemp("argos_sensing"))
    source = project.folder / (project.name + "_controller.cpp")
    stubs = iter(range(1000))
    source.write_text(re.sub(r"return false;", lambda _: NEIGHBOURS % (next(stubs) % 3), source.read_text()))
    build(project, "g++", "-DARGOS_PREFIX=%s" % argos_prefix)
    return project


def test_generated_experiment_runs_as_it_is(network_worker):
    project, _ = network_worker
    status, log, err = run_argos(project, project.folder / (project.name + ".argos"))
    assert status == 0, err
    summaries = robot_lines(log, "summary")
    assert sorted(summaries) == ["ep%d" % i for i in range(6)]
    for (line,) in summaries.values():
        steps, fired, _, violations = SUMMARY.fullmatch(line).groups()
        assert (int(steps), int(violations)) == (300, 0)
        assert int(fired) > 0


def test_one_seed_one_output(sensing_worker):
    def run(seed):
        status, log, err = run_argos(sensing_worker, experiment(
            sensing_worker, "seed%d" % seed, robots=10, random_seed=seed, options={"inputs": "edge"},
            report={"trace": "true", "summary": "true"}))
        assert status == 0, err
        return log

    first, again, other = run(5), run(5), run(6)
    assert len(robot_lines(first, "trace")["ep9"]) == 300
    assert re.search(r"EV_accept [1-9]", first)   # the filled-in checks fired
    assert first == again
    assert robot_lines(first, "trace") != robot_lines(other, "trace")
