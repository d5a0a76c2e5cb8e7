"""The files swarmvm ships beside its code: templates, runtimes, and the Python VM as a module.

The top-level folders ``templates/``, ``runtime_c/``, ``runtime_cpp/`` and ``runtime_py/`` are
installed as the packages ``swarmvm.templates``, ``swarmvm.runtime_c``, ... (pyproject.toml's
``package-dir``), so they are found through :mod:`importlib.resources` in a wheel, an editable
install and a source checkout alike, never through a path computed from this file."""

import sys
from functools import lru_cache
from importlib import import_module, resources
from importlib.abc import Traversable
from types import ModuleType

TEMPLATES: Traversable = resources.files("swarmvm.templates")
RUNTIME_C: Traversable = resources.files("swarmvm.runtime_c")
RUNTIME_CPP: Traversable = resources.files("swarmvm.runtime_cpp")
RUNTIME_PY_DIR: Traversable = resources.files("swarmvm.runtime_py")
RUNTIME_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_vm.py"
RUNTIME_LEARN_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_learn.py"


@lru_cache(maxsize=None)
def python_vm() -> ModuleType:
    """The reference Python VM (runtime_py/swarmvm_vm.py).

    It is also registered as the top-level module ``swarmvm_vm``, the name generated Python
    targets import it by, so that generated code loaded in this process shares its classes
    (an ``ImageError`` raised there is the one the compiler catches)."""
    module = sys.modules.get("swarmvm_vm") or import_module("swarmvm.runtime_py.swarmvm_vm")
    sys.modules.setdefault("swarmvm_vm", module)
    return module
