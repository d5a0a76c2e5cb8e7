"""The baseline the speed benchmarks compare against: the runtimes as they were at commit
BASELINE (main before the speed work of issue 13), taken from this checkout's git history into
a scratch folder so that both versions run side by side in one benchmark run.

It stays the old commit's code, not the reference VM (runtime_py/swarmvm_reference.py): issue
13's targets are ratios to that commit's speed. The plain step of docs/semantics.md, to read
and to compare traces with, is the reference; benchmarks/python_vm.py measures the VM against
it too."""

import importlib.util
import subprocess
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parent.parent
BASELINE = "e4f6e67"


def baseline_file(path: str, scratch: Path) -> Path:
    """``path`` (relative to the checkout) as it was at BASELINE, written under ``scratch``."""
    result = subprocess.run(["git", "-C", str(ROOT), "show", "%s:%s" % (BASELINE, path)], capture_output=True)
    if result.returncode != 0:
        sys.exit("bench: the baseline needs this checkout's git history (commit %s): %s"
                 % (BASELINE, result.stderr.decode(errors="replace").strip()))
    out = scratch / ("baseline-" + BASELINE) / path
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(result.stdout)
    return out


def baseline_python_vm(scratch: Path) -> ModuleType:
    """The baseline's Python VM module (it was one self-contained file)."""
    path = baseline_file("runtime_py/swarmvm_vm.py", scratch)
    spec = importlib.util.spec_from_file_location("baseline_swarmvm_vm", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def baseline_tree(scratch: Path, folders=("runtime_c", "runtime_cpp", "firmware/harness", "firmware/capbot")) -> Path:
    """The baseline's ``folders`` (every file in them at BASELINE) under one root in
    ``scratch``, laid out as in a checkout: build it side by side with the current sources."""
    listing = subprocess.run(["git", "-C", str(ROOT), "ls-tree", "-r", "--name-only", BASELINE, "--", *folders],
                             capture_output=True, text=True)
    if listing.returncode != 0 or not listing.stdout.strip():
        sys.exit("bench: the baseline needs this checkout's git history (commit %s)" % BASELINE)
    for path in listing.stdout.split():
        baseline_file(path, scratch)
    return scratch / ("baseline-" + BASELINE)
