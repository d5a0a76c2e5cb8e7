"""What the inspector's tests (docs/inspect.md) share: corpus supervisors, traces written by the
reference VM, and ``swarmvm`` run as a user runs it."""

import subprocess
import sys
from pathlib import Path

from swarmvm import api

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus"
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
FLIPFLOP = CORPUS / "nadzoru2" / "flipflop_S.yaml"          # its random scripts make violations
NETWORK_WORKER = CORPUS / "openswarm" / "network_worker.yaml"  # 8 supervisors, up to 54 states
HITL_LEADER = CORPUS / "openswarm" / "hitl_leader.yaml"        # up to 4 controllable events enabled at once
SCREENSHOTS = ROOT / "build" / "inspect-screenshots"


def write_trace(folder: Path, supervisor: Path, steps: int, seed: int, name: str, density: float = 0.25) -> Path:
    """A trace of the reference VM on a random script (``swarmvm script`` / ``swarmvm trace``)."""
    script = folder / (name + ".script")
    script.write_text(api.make_script([str(supervisor)], steps, seed, density))
    path = folder / name
    path.write_text("".join(line + "\n" for line in api.trace([str(supervisor)], str(script), seed=seed)))
    return path


def trace_lines(path: Path) -> list:
    """A trace's lines split as docs/conformance.md says: (step, events, states, violations)."""
    rows = []
    for line in path.read_text().splitlines():
        step, events, states, violations = line.split()
        rows.append((int(step), [] if events == "-" else events.split(","), [int(s) for s in states.split(",")],
                     int(violations)))
    return rows


def swarmvm(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "swarmvm", *args], capture_output=True, text=True, cwd=cwd)
