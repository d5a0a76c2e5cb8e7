"""Where the runtimes, templates and firmware live, and the Python VM as a module.

swarmvm is used from its checkout (``pip install -e .``): these folders sit beside
``generator/`` at the top of the repository."""

import importlib.util
import sys
from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TEMPLATES = ROOT / "templates"
RUNTIME_PY = ROOT / "runtime_py" / "swarmvm_vm.py"
RUNTIME_LEARN_PY = ROOT / "runtime_py" / "swarmvm_learn.py"
RUNTIME_C = ROOT / "runtime_c"
RUNTIME_CPP = ROOT / "runtime_cpp"
FIRMWARE = ROOT / "firmware"


@lru_cache(maxsize=None)
def python_vm():
    """The reference Python VM module (runtime_py/swarmvm_vm.py), imported once."""
    if "swarmvm_vm" in sys.modules:
        return sys.modules["swarmvm_vm"]
    spec = importlib.util.spec_from_file_location("swarmvm_vm", RUNTIME_PY)
    module = importlib.util.module_from_spec(spec)
    sys.modules["swarmvm_vm"] = module
    spec.loader.exec_module(module)
    return module
