"""`swarmvm gen --target pipuck`: the generated Pi-puck controller runs the VM against the
simulated adapter (its trace equals the reference), logs motor and LED commands, imports the
hardware library only when the real robot is used, and calls that library's API."""

import subprocess
import sys
from pathlib import Path

import pytest

from checkout import ROOT

SUPERVISOR = ROOT / "tests" / "corpus" / "openswarm" / "capbot_demo.yaml"
STEPS = 20


def gen(outdir):
    subprocess.run(["swarmvm", "gen", str(SUPERVISOR), "--target", "pipuck", "-o", str(outdir)],
                   check=True, capture_output=True)
    return Path(outdir)


def controller(outdir, *args, env=None):
    return subprocess.run([sys.executable, "-m", "capbot_demo_app"] + list(args), cwd=str(outdir),
                          capture_output=True, text=True, env=env)


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    return gen(tmp_path_factory.mktemp("pipuck"))


@pytest.mark.parametrize("seed,density", [(3, 0.3), (11, 0.6)])
def test_sim_run_prints_the_reference_trace(out, seed, density):
    script = out / ("script_%d.txt" % seed)
    script.write_text(subprocess.run(["swarmvm", "script", str(SUPERVISOR), "--steps", str(STEPS), "--seed",
                                      str(seed), "--density", str(density)],
                                     check=True, capture_output=True, text=True).stdout)
    reference = subprocess.run(["swarmvm", "trace", str(SUPERVISOR), "--script", str(script), "--seed", "5"],
                               check=True, capture_output=True, text=True).stdout.splitlines()
    result = controller(out, "--sim", "--steps", str(STEPS), "--period", "0", "--script", script.name,
                        "--seed", "5", "--trace")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    trace = [line for line in lines if not line.startswith("sim ")]
    assert trace == reference
    actions = sum(line.split()[1].count("EV_move") + line.split()[1].count("EV_stop") for line in trace)
    assert actions > 0, "the script never let the VM act"
    motors = [line for line in lines if line.startswith("sim motors")]
    assert len(motors) == actions + 1          # one per action, one when the loop stops
    assert motors[-1] == "sim motors 0 0" and lines[-1] == "sim leds off"


def test_sim_runs_for_the_given_steps_without_a_script(out):
    result = controller(out, "--sim", "--steps", str(STEPS), "--period", "0.001", "--trace")
    assert result.returncode == 0, result.stderr
    trace = [line for line in result.stdout.splitlines() if not line.startswith("sim ")]
    assert [line.split()[0] for line in trace] == [str(n) for n in range(1, STEPS + 1)]


def test_hardware_library_is_imported_lazily(out):
    probe = "import sys, capbot_demo_app; print('pipuck' in sys.modules, 'smbus' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", probe], cwd=str(out), capture_output=True, text=True)
    assert result.stdout.split() == ["False", "False"], result.stderr
    result = controller(out, "--steps", "1")
    assert result.returncode != 0
    assert "pipuck library is not available" in result.stderr and "--sim" in result.stderr


def hardware_stand_in(tmp_path):
    """A stand-in for the pipuck hardware library (no real one runs off the robot): it prints
    the calls of the pipuck API that the real adapter makes. Returns the environment to run with."""
    package = tmp_path / "pipuck"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "pipuck.py").write_text(
        "class _EPuck:\n"
        "    def set_motor_speeds(self, left, right):\n"
        "        print('lib set_motor_speeds', left, right)\n"
        "class PiPuck:\n"
        "    def __init__(self, epuck_version):\n"
        "        print('lib PiPuck', epuck_version)\n"
        "        self.epuck = _EPuck()\n"
        "    def set_leds_colour(self, colour):\n"
        "        print('lib set_leds_colour', colour)\n")
    return {"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"}


def test_real_adapter_drives_the_pipuck_library(out, tmp_path):
    """With a stand-in for the hardware library on the path, the real adapter makes the calls of
    the pipuck API (PiPuck(epuck_version=2), epuck.set_motor_speeds, set_leds_colour)."""
    result = controller(out, "--steps", "2", "--period", "0", env=hardware_stand_in(tmp_path))
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["lib PiPuck 2", "lib set_motor_speeds 0 0", "lib set_leds_colour off"]


def test_real_adapter_hears_robots_and_ignores_other_datagrams(out, tmp_path):
    """Real UDP datagrams to the message port: what is not a robot's broadcast (not UTF-8, not
    JSON, not an object, no string message, longer than any broadcast) is ignored, not a
    traceback that stops the robot; the longest name (255 characters) arrives whole (datagrams
    were read to 256 bytes: its broadcast, 270, failed to parse)."""
    probe = (
        "import json, socket, swarmvm_pipuck as p\n"
        "robot = p.PiPuckRobot()\n"
        "sender = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)\n"
        "longest = 'n' * 255\n"
        "for datagram in (b'\\xff\\xfe', b'not json', b'[1, 2]', b'{\"other\": 1}', b'{\"message\": [1]}',\n"
        "                 json.dumps({'message': 'y' * 5000}).encode(), json.dumps({'message': longest}).encode(),\n"
        "                 json.dumps({'message': 'go'}).encode()):\n"
        "    sender.sendto(datagram, ('127.0.0.1', p.MESSAGE_PORT))\n"
        "robot.begin_step(1)\n"
        "print(robot.received('go'), robot.received(longest), robot.received('y' * 5000))\n")
    result = subprocess.run([sys.executable, "-c", probe], cwd=str(out), capture_output=True, text=True,
                            env=hardware_stand_in(tmp_path), timeout=30)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["lib PiPuck 2", "True True False"]


def test_generation_is_deterministic_and_keeps_the_controller(tmp_path):
    first, second = gen(tmp_path / "a"), gen(tmp_path / "b")
    for path in sorted(first.iterdir()):
        assert path.read_bytes() == (second / path.name).read_bytes(), path.name
    edited = (first / "capbot_demo_controller.py").read_text() + "# user code\n"
    (first / "capbot_demo_controller.py").write_text(edited)
    gen(first)
    assert (first / "capbot_demo_controller.py").read_text() == edited
