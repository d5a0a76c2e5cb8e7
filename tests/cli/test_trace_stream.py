"""`swarmvm trace` streams: a script of any length (up to the ten million steps `swarmvm script`
writes) is replayed line by line in constant memory, after a first pass over the file that
refuses bad input before the first line of output. Memory is measured in the subprocess
(its peak resident set, from /proc), not by wall time."""

import subprocess
import sys

import pytest

from checkout import EXAMPLE
from swarmvm import api
from swarmvm.boundary.errors import MAX_BYTES
from swarmvm.compiler.runtime_files import python_vm
from swarmvm.readers.event_script import MAX_LINE_BYTES, MAX_STEPS, parse_script

STEPS = MAX_STEPS
PEAK_LIMIT_KB = 100 * 1024


def write_script(path, steps, last=None):
    """A script of ``steps`` steps: a 1,000-step random script repeated (written in large
    blocks: seconds for ten million lines), its last step ``last`` when given. Returns the
    script's text for its first 1,000 steps."""
    lines = list(api.script_lines([str(EXAMPLE)], 1000, seed=5))[1:]
    block = "".join(line + "\n" for line in lines)
    body = steps - (last is not None)
    with open(path, "w") as out:
        out.write("# %d steps\n" % steps)
        for _ in range(body // len(lines)):
            out.write(block)
        out.write("".join(line + "\n" for line in lines[:body % len(lines)]))
        if last is not None:
            out.write(last + "\n")
    return block


def peak_kb(pid):
    """The peak resident set of a running process, in kB (VmHWM)."""
    with open("/proc/%d/status" % pid) as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:"))


def test_a_script_over_the_input_size_limit_traces_like_the_same_rows_in_memory(tmp_path):
    script = tmp_path / "s.txt"
    block = write_script(script, 60000)
    assert script.stat().st_size > MAX_BYTES
    compiled = api.compile_model([str(EXAMPLE)])
    rows = parse_script("s", block, compiled.model.events, compiled.tables.controllable) * 60
    vm = python_vm()
    assert list(api.trace([str(EXAMPLE)], str(script), seed=3)) == vm.replay(vm.VM(compiled.image, seed=3), rows)


def test_bad_input_on_the_last_line_of_a_long_script_is_refused_before_any_output(tmp_path):
    script = tmp_path / "s.txt"
    write_script(script, 300000, last="EV_noSuchEvent")
    result = subprocess.run([sys.executable, "-m", "swarmvm", "trace", str(EXAMPLE), "--script", str(script)],
                            capture_output=True, text=True)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == "swarmvm: error: %s: line 300001: event EV_noSuchEvent: unknown event\n" % script


@pytest.mark.slow
def test_ten_million_steps_trace_in_constant_memory(tmp_path):
    """The first pass reads all ten million lines and the replay a million of them while the
    peak resident set stays under 100 MB (the rows of ten million steps as a list: 2.6 GB)."""
    script = tmp_path / "s.txt"
    write_script(script, STEPS)
    proc = subprocess.Popen([sys.executable, "-m", "swarmvm", "trace", str(EXAMPLE), "--script", str(script)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = proc.stdout.readline()
        for _ in range(10 ** 6):
            last = proc.stdout.readline()
        peak = peak_kb(proc.pid)
    finally:
        proc.kill()
        proc.wait()
    assert first.startswith("1 ") and last.startswith("1000001 "), (first, last, proc.stderr.read())
    print("peak resident set %d kB" % peak)
    assert peak < PEAK_LIMIT_KB, "peak resident set %d kB" % peak


def test_a_line_over_the_line_limit_is_refused_before_any_output(tmp_path):
    script = tmp_path / "s.txt"
    script.write_text("-\n" * 10 + "EV_" + "x" * MAX_LINE_BYTES + "\n")
    result = subprocess.run([sys.executable, "-m", "swarmvm", "trace", str(EXAMPLE), "--script", str(script)],
                            capture_output=True, text=True)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == "swarmvm: error: %s: line 11: line over the %d-byte limit\n" % (script, MAX_LINE_BYTES)


@pytest.mark.slow
def test_a_script_over_ten_million_steps_is_refused_before_any_output(tmp_path):
    script = tmp_path / "s.txt"
    script.write_text("# one step too many\n" + "-\n" * (MAX_STEPS + 1))
    result = subprocess.run([sys.executable, "-m", "swarmvm", "trace", str(EXAMPLE), "--script", str(script)],
                            capture_output=True, text=True)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == "swarmvm: error: %s: script of over %d steps\n" % (script, MAX_STEPS)
