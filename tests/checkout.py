"""Paths in the source checkout that tests build from: firmware glue and harnesses, which the
installed package does not ship (it ships templates and runtimes, found through swarmvm.compiler.runtime_files)."""

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIRMWARE = ROOT / "firmware"
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
