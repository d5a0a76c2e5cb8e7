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
from typing import Dict

TEMPLATES: Traversable = resources.files("swarmvm.templates")
RUNTIME_C: Traversable = resources.files("swarmvm.runtime_c")
RUNTIME_CPP: Traversable = resources.files("swarmvm.runtime_cpp")
RUNTIME_PY_DIR: Traversable = resources.files("swarmvm.runtime_py")
RUNTIME_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_vm.py"
RUNTIME_FORMAT_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_format.py"
RUNTIME_LEARN_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_learn.py"


@lru_cache(maxsize=None)
def image_format() -> ModuleType:
    """The table image format's one definition (runtime_py/swarmvm_format.py): its constants,
    error codes, writer (``assemble``) and reader (``Image``). A plain import of the package's
    own module (it imports the standard library only)."""
    return import_module("swarmvm.runtime_py.swarmvm_format")


def _runtime_module(name: str, neighbours: Dict[str, ModuleType]) -> ModuleType:
    """The package's runtime_py/``name``.py, imported with the top-level names a robot's copy
    imports its neighbours by (``from swarmvm_format import ...``) bound to the package's own
    modules for the import only; the previous entries (none, or another copy a program loaded)
    come back after it. So the runtime and the compiler share one ``Image`` and ``ImageError``,
    and loading it registers no top-level module: a generated Python target imported in the same
    process still finds its own copy of the runtime."""
    previous = {neighbour: sys.modules.get(neighbour) for neighbour in neighbours}
    sys.modules.update(neighbours)
    try:
        return import_module("swarmvm.runtime_py." + name)
    finally:
        for neighbour, module in previous.items():
            if module is None:
                del sys.modules[neighbour]
            else:
                sys.modules[neighbour] = module


@lru_cache(maxsize=None)
def python_vm() -> ModuleType:
    """The fast Python VM (runtime_py/swarmvm_vm.py), loaded on first use."""
    return _runtime_module("swarmvm_vm", {"swarmvm_format": image_format()})


@lru_cache(maxsize=None)
def reference_vm() -> ModuleType:
    """The plain reference VM (runtime_py/swarmvm_reference.py), the conformance oracle."""
    return _runtime_module("swarmvm_reference", {"swarmvm_format": image_format(), "swarmvm_vm": python_vm()})
