"""The files swarmvm ships beside its code: templates, runtimes, and the Python VM as a module.

The top-level folders ``templates/``, ``runtime_c/``, ``runtime_cpp/`` and ``runtime_py/`` are
installed as the packages ``swarmvm.templates``, ``swarmvm.runtime_c``, ... (pyproject.toml's
``package-dir``), so they are found through :mod:`importlib.resources` in a wheel, an editable
install and a source checkout alike, never through a path computed from this file."""

import sys
import threading
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
RUNTIME_STEP_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_step_source.py"
RUNTIME_LEARN_PY: Traversable = RUNTIME_PY_DIR / "swarmvm_learn.py"

# The C++ runtime's headers (runtime_cpp/): the VM (the format's generated numbers, the image and
# its reader, the VM itself), the compatibility layer of published SCT programs, and swarmvm.hpp,
# the umbrella that includes them all. A target ships all of them; the footprint report counts
# the VM's apart from the compatibility layer's.
CPP_VM_HEADERS = ("swarmvm_format.hpp", "swarmvm_image.hpp", "swarmvm_vm.hpp")
CPP_COMPAT_HEADERS = ("swarmvm_compat.hpp",)
CPP_RUNTIME_HEADERS = CPP_VM_HEADERS + CPP_COMPAT_HEADERS + ("swarmvm.hpp",)


@lru_cache(maxsize=None)
def image_format() -> ModuleType:
    """The table image format's one definition (runtime_py/swarmvm_format.py): its constants,
    error codes, writer (``assemble``) and reader (``Image``). A plain import of the package's
    own module (it imports the standard library only)."""
    return import_module("swarmvm.runtime_py.swarmvm_format")


# sys.modules is the process's: two threads binding and restoring the neighbours at once would
# each restore what the other bound (the package's swarmvm_vm left registered). One at a time.
_BINDING = threading.RLock()


def _runtime_module(name: str, neighbours: Dict[str, ModuleType]) -> ModuleType:
    """The package's runtime_py/``name``.py, imported with the top-level names a robot's copy
    imports its neighbours by (``from swarmvm_format import ...``) bound to the package's own
    modules for the import only; the previous entries (none, or another copy a program loaded)
    come back after it. So the runtime and the compiler share one ``Image`` and ``ImageError``,
    and loading it registers no top-level module: a generated Python target imported in the same
    process still finds its own copy of the runtime."""
    with _BINDING:
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
def step_source() -> ModuleType:
    """The fast Python VM's step writer (runtime_py/swarmvm_step_source.py, standard library only)."""
    return import_module("swarmvm.runtime_py.swarmvm_step_source")


@lru_cache(maxsize=None)
def python_vm() -> ModuleType:
    """The fast Python VM (runtime_py/swarmvm_vm.py), loaded on first use."""
    return _runtime_module("swarmvm_vm", {"swarmvm_format": image_format(), "swarmvm_step_source": step_source()})


@lru_cache(maxsize=None)
def learning() -> ModuleType:
    """The learning runtime (runtime_py/swarmvm_learn.py: the classifier of learned checks and
    policy ``learned``), loaded on first use."""
    return _runtime_module("swarmvm_learn", {"swarmvm_format": image_format()})


@lru_cache(maxsize=None)
def python_app() -> ModuleType:
    """What the generated Python apps share (runtime_py/swarmvm_app.py), loaded on first use: the
    home of the facts the apps and the compiler's command line both state (the seed range, the
    policies an option offers), as a robot carries no compiler to import them from."""
    return _runtime_module("swarmvm_app", {"swarmvm_vm": python_vm()})


@lru_cache(maxsize=None)
def reference_vm() -> ModuleType:
    """The plain reference VM (runtime_py/swarmvm_reference.py), the conformance oracle."""
    return _runtime_module("swarmvm_reference", {"swarmvm_format": image_format(), "swarmvm_vm": python_vm()})
