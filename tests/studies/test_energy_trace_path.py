"""`swarmvm sim energy --trace FILE` writes FILE relative to the caller's folder (issue 27: ARGoS
runs in a temporary folder, removed after the trial, so a relative path wrote the trace there and
lost it, exit status 0); a trace that cannot be written is an error, not a silent success. Real
ARGoS, 5 simulated seconds."""

import subprocess
import sys

import pytest



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
