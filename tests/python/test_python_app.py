"""`python3 -m <name>_app` of the python target takes options (issue 27: `--help` stepped for
ever, printing nothing): --help answers and exits, --steps stops, --script replays an event script
(from a file or standard input) with the trace `swarmvm trace` prints, and without --steps the
app says on stderr that it runs until stopped, and stops on Ctrl-C without a traceback. The
Pi-puck app parses the same options (swarmvm_app.py, shipped in both targets)."""

import select
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from checkout import EXAMPLE, ROOT

OPTIONS = ("--steps", "--period", "--seed", "--inputs", "--control", "--policy", "--script", "--trace")


def gen(target: str, out: Path) -> Path:
    subprocess.run(["swarmvm", "gen", str(EXAMPLE), "--target", target, "-o", str(out), "--name", "worker"],
                   check=True, capture_output=True)
    return out


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    return gen("python", tmp_path_factory.mktemp("python_app"))


def run(folder: Path, *args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "worker_app", *args], cwd=folder, capture_output=True, text=True,
                          input=stdin, timeout=20)


def test_help_prints_the_options_and_exits(app):
    result = run(app, "--help")
    assert result.returncode == 0 and result.stdout.startswith("usage: ")
    assert all(option in result.stdout for option in OPTIONS)


def test_steps_stops_after_that_many_steps(app):
    result = run(app, "--steps", "7", "--period", "0", "--trace")
    assert result.returncode == 0 and result.stderr == ""
    assert [line.split()[0] for line in result.stdout.splitlines()] == [str(n) for n in range(1, 8)]


def test_a_bad_option_value_is_a_usage_error(app):
    result = run(app, "--steps", "0")
    assert result.returncode == 2 and "--steps: '0' is not a positive number of steps" in result.stderr


@pytest.mark.parametrize("option, good, bad", [("--seed", "4294967295", "4294967296"), ("--policy", "weighted", "learned")])
def test_the_app_and_swarmvm_trace_take_the_same_seeds_and_policies(app, tmp_path, option, good, bad):
    """One range of seeds and one list of policies (runtime_py/swarmvm_app.py), in the app and in
    ``swarmvm trace`` alike: the last good value runs in both, the first bad one is refused by both."""
    (tmp_path / "events.txt").write_text("-\n")
    trace = ["swarmvm", "trace", str(EXAMPLE), "--script", str(tmp_path / "events.txt"), option]
    for value, status in ((good, 0), (bad, 2)):
        assert run(app, "--steps", "1", "--period", "0", option, value).returncode == status, value
        assert subprocess.run(trace + [value], capture_output=True, text=True).returncode == status, value


@pytest.mark.parametrize("source", ["file", "stdin"])
def test_script_replays_with_the_trace_swarmvm_trace_prints(app, source):
    script = subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "30", "--seed", "9", "--density", "0.4"],
                            check=True, capture_output=True, text=True).stdout
    (app / "events.txt").write_text(script)
    reference = subprocess.run(["swarmvm", "trace", str(EXAMPLE), "--script", str(app / "events.txt"), "--seed", "4"],
                               check=True, capture_output=True, text=True).stdout
    args = ["--script", "events.txt" if source == "file" else "-", "--steps", "30", "--seed", "4", "--period", "0",
            "--trace"]
    result = run(app, *args, stdin=script if source == "stdin" else None)
    assert result.returncode == 0, result.stderr
    assert result.stdout == reference and "EV_" in reference


def test_an_unknown_event_in_the_script_is_one_line(app):
    result = run(app, "--script", "-", "--steps", "2", stdin="EV_bogus\n")
    assert result.returncode == 1 and result.stderr == "-:1: unknown event EV_bogus\n"


def test_without_steps_it_says_it_runs_until_stopped_and_stops_on_ctrl_c(app):
    process = subprocess.Popen([sys.executable, "-m", "worker_app", "--period", "0.01", "--trace"], cwd=app,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        said = select.select([process.stderr], [], [], 30)[0]      # said before the first step, or never
        first = process.stderr.readline() if said else ""
        # Ctrl-C once the loop runs (CPython counts an interrupt that lands while the VM compiles
        # its step, in step 1, as unhandled, and then exits by the signal whatever caught it).
        line = "-"
        while line and not line.startswith("3 ") and select.select([process.stdout], [], [], 30)[0]:
            line = process.stdout.readline()        # "" at the end of the output: it stopped by itself
    finally:
        process.send_signal(signal.SIGINT)
        try:
            _out, rest = process.communicate(timeout=30)
        finally:
            process.kill()
    assert first == "worker_app.py: stepping the VM until stopped (Ctrl-C; --steps N stops after N steps, " \
                    "--help lists the options)\n"
    assert process.returncode == 0 and "Traceback" not in rest and rest.startswith("worker_app.py: stopped in step ")


def test_the_pipuck_app_parses_the_same_options(tmp_path):
    out = gen("pipuck", tmp_path)
    result = run(out, "--help")
    assert result.returncode == 0 and all(option in result.stdout for option in OPTIONS + ("--sim",))
    refused = run(out, "--script", "events.txt", "--steps", "1")
    assert refused.returncode == 2 and "--script needs --sim" in refused.stderr
    assert (out / "swarmvm_app.py").read_bytes().endswith((ROOT / "runtime_py" / "swarmvm_app.py").read_bytes())
