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
RUNTIME_FORMAT_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_format.py"
RUNTIME_LEARN_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_learn.py"


@lru_cache(maxsize=None)
def image_format() -> ModuleType:
    """The table image format's one definition (runtime_py/swarmvm_format.py): its constants,
    error codes, writer (``assemble``) and reader (``Image``). A plain import of the package's
    own module (it imports the standard library only)."""
    return import_module("swarmvm.runtime_py.swarmvm_format")


@lru_cache(maxsize=None)
def python_vm() -> ModuleType:
    """The reference Python VM (runtime_py/swarmvm_vm.py), loaded on first use.

    The file imports the format by the top-level name a robot's copy has beside it
    (``from swarmvm_format import ...``); here that name is the package's format module for the
    import only, and the previous entry (none, or another copy a program loaded) comes back
    after it. So the VM and the compiler share one ``Image`` and ``ImageError``, and loading
    the VM registers no top-level module: a generated Python target imported in the same
    process still finds its own copy of the runtime."""
    name = "swarmvm_format"
    previous = sys.modules.get(name)
    sys.modules[name] = image_format()
    try:
        return import_module("swarmvm.runtime_py.swarmvm_vm")
    finally:
        if previous is None:
            del sys.modules[name]
        else:
            sys.modules[name] = previous
