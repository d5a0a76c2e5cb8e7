"""`swarmvm sim energy --trace FILE` writes FILE relative to the caller's folder (issue 27: ARGoS
runs in a temporary folder, removed after the trial, so a relative path wrote the trace there and
lost it, exit status 0); a trace that cannot be written is an error, not a silent success. Real
ARGoS, 5 simulated seconds."""

import subprocess
import sys
from pathlib import Path

import pytest

from conformance.inspected import inspected_states, states_of
from swarmvm.studies import energy_replenishment

SUPERVISORS = Path(energy_replenishment.__file__).parent / "supervisors"



def sim_energy(folder, *args):
    return subprocess.run([sys.executable, "-m", "swarmvm", "sim", "energy", "--duration", "5", *args], cwd=folder,
                          capture_output=True, text=True)


@pytest.mark.emulator
def test_a_relative_trace_is_written_in_the_callers_folder(library, tmp_path):
    result = sim_energy(tmp_path, "--trace", "trace.csv")
    assert result.returncode == 0, result.stderr
    rows = (tmp_path / "trace.csv").read_text().splitlines()
    assert rows[0].startswith("step,id,") and len(rows) == 1 + 50 * 6      # 50 steps of 6 workers


@pytest.mark.emulator
def test_a_trace_that_cannot_be_written_is_an_error(library, tmp_path):
    result = sim_energy(tmp_path, "--trace", "no_such_folder/trace.csv")
    assert (result.returncode, result.stdout) == (1, "")
    assert result.stderr.startswith("swarmvm: error: energy: argos3 wrote no trace to ")


@pytest.mark.emulator
def test_vm_traces_are_written_per_supervisor_and_inspected(library, tmp_path):
    """--vm-traces: each robot's canonical trace, SUPERVISOR/ROBOT.trace; swarmvm inspect reads a
    supervisor's traces as one lane per robot, and every step holds the states its trace gives."""
    result = sim_energy(tmp_path, "--strategy", "mobile", "--workers", "2", "--chargers", "1", "--vm-traces", "vm")
    assert result.returncode == 0, result.stderr
    found = {p.relative_to(tmp_path / "vm").as_posix() for p in (tmp_path / "vm").rglob("*.trace")}
    assert found == {"energy_worker_mc/w0.trace", "energy_worker_mc/w1.trace", "energy_charger/c0.trace"}
    traces = {p.stem: p.read_text().splitlines() for p in (tmp_path / "vm" / "energy_worker_mc").glob("*.trace")}
    assert [len(lines) for lines in traces.values()] == [50, 50]                  # 5 s at 10 steps a second
    assert inspected_states(SUPERVISORS / "energy_worker_mc.yaml", traces, tmp_path) == states_of(traces)


def test_vm_traces_onto_a_file_is_one_line(tmp_path):
    (tmp_path / "vm").write_text("")
    result = sim_energy(tmp_path, "--vm-traces", "vm")
    assert result.returncode == 2 and result.stderr.count("\n") == 1 and "vm" in result.stderr, result.stderr
