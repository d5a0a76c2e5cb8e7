"""`swarmvm gen --learned-check`: uav.yaml's capableTask/notCapableTask pair decided by the
online classifier. The generated controller runs; on every task announcement exactly one of
the pair fires, capableTask iff the classifier says yes; each reported delivery outcome is one
partial_fit (the classifier ends where an independent one fed the same samples ends)."""

import json
import os
import subprocess
import sys

from click.testing import CliRunner

from drone import MEAN, SCALE, SEED_LABELS, SEED_POINTS, delivery_stream
from swarmvm.cli.commands import main as cli
from swarmvm_learn import LinearClassifier

HERE = os.path.dirname(os.path.abspath(__file__))
UAV = os.path.join(HERE, "..", "corpus", "openswarm", "uav.yaml")


def generate(outdir, *extra):
    return CliRunner().invoke(cli, ["gen", UAV, "--target", "python", "-o", str(outdir), *extra])


def drive(outdir, tasks):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(outdir), HERE]))
    done = subprocess.run([sys.executable, os.path.join(HERE, "scenarios", "uav_deliveries.py"), str(tasks)],
                          cwd=str(outdir), env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_generated_uav_controller_decides_and_learns(tmp_path):
    result = generate(tmp_path, "--learned-check", "capableTask/notCapableTask")
    assert result.exit_code == 0, result.output
    assert (tmp_path / "uav_learned.py").exists() and (tmp_path / "swarmvm_learn.py").exists()
    run = drive(tmp_path, 400)

    reference = LinearClassifier(MEAN, SCALE, alpha=0.01)
    reference.fit(SEED_POINTS, SEED_LABELS)
    expected = []
    for features, delivered in delivery_stream(400, seed=21):
        yes = reference.decide(features)
        expected.append(yes)
        if yes:
            reference.partial_fit(features, int(delivered))
    assert run["decisions"] == expected
    assert 50 < sum(expected) < 350                     # both answers occur
    assert run["outcomes"] == sum(expected)
    assert run["classifier"]["weights"] == reference.weights
    assert run["classifier"]["intercept"] == reference.intercept
    assert run["classifier"]["t"] == 175.0 + sum(expected)
    # the supervisor follows the intended cycle, never violated
    assert run["violations"] == 0 and run["states"] == [0]
    for fired, yes in zip((s for s in run["steps"] if "capableTask" in s or "notCapableTask" in s), expected):
        assert fired == (["capableTask", "bid"] if yes else ["notCapableTask"])
    assert ["wonBid", "deliver"] in run["steps"] and ["condReturn", "return"] in run["steps"]


def test_learned_check_option_is_validated(tmp_path):
    for spec, message in [("capableTask", "is not YES/NO"), ("capableTask/capableTask", "is not YES/NO"),
                          ("capableTask/nope", "no event named 'nope'"), ("bid/notCapableTask", "bid is controllable")]:
        result = generate(tmp_path, "--learned-check", spec)
        assert result.exit_code == 2 and message in result.output, (spec, result.output)
    assert not any(tmp_path.iterdir())
    result = CliRunner().invoke(cli, ["gen", UAV, "--target", "argos", "-o", str(tmp_path),
                                      "--learned-check", "capableTask/notCapableTask"])
    assert result.exit_code == 2 and "does not generate learned checks" in result.output


def test_without_the_option_nothing_learned_is_generated(tmp_path):
    assert generate(tmp_path).exit_code == 0
    assert not (tmp_path / "uav_learned.py").exists()
    assert "learned" not in (tmp_path / "uav_controller.py").read_text()
