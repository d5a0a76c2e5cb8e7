"""The Pi-puck target (templates/pipuck/, docs/robots/pipuck.md): the python target's tables and
VM with the robot's adapters (real, and ``--sim``) and a fixed-rate app."""

from ..compiler.runtime_files import RUNTIME_PY_DIR, TEMPLATES
from .python import PY_RUNTIME_COPIES
from .record import Target

TARGET = Target(
    "pipuck",
    "Pi-puck controller (Python): tables, the Python VM, robot adapters (real and --sim), fixed-rate app, controller skeleton",
    templates=(("python/tables.py.j2", "{name}_tables.py", False),
               ("pipuck/app.py.j2", "{name}_app.py", False),
               ("pipuck/controller.py.j2", "{name}_controller.py", True)),
    template_folder=TEMPLATES / "pipuck",
    page="robots/pipuck.md",
    copies=PY_RUNTIME_COPIES + ((RUNTIME_PY_DIR / "swarmvm_pipuck.py", "swarmvm_pipuck.py"),),
    keeps_order=True)
