"""The Pi-puck target (templates/pipuck/, docs/robots/pipuck.md): the python target's tables and
VM with the robot's adapters (real, and ``--sim``) and a fixed-rate app."""

from ..compiler.runtime_files import RUNTIME_PY_DIR, TEMPLATES
from .python import PY_RUNTIME_COPIES
from .record import Readme, Target

TARGET = Target(
    "pipuck",
    "Pi-puck controller (Python): tables, the Python VM, robot adapters (real and --sim), fixed-rate app, controller skeleton",
    templates=(("python/tables.py.j2", "{name}_tables.py", False),
               ("pipuck/app.py.j2", "{name}_app.py", False),
               ("pipuck/controller.py.j2", "{name}_controller.py", True)),
    template_folder=TEMPLATES / "pipuck",
    page="robots/pipuck.md",
    copies=PY_RUNTIME_COPIES + ((RUNTIME_PY_DIR / "swarmvm_pipuck.py", "swarmvm_pipuck.py"),),
    keeps_order=True,
    readme=Readme("pipuck/readme.md.j2", (
        ("{name}_tables.py", "the table image as bytes, event constants"),
        ("{name}_app.py", "python3 -m {name}_app: binds your controller, the fixed-rate loop, --sim"),
        ("{name}_controller.py", "class Controller(robot): check_EVENT (True when it occurred; message events are "
                                 "answered from what the robot heard) and on_EVENT (the robot's action; message "
                                 "events broadcast)"),
        ("swarmvm_*.py", "the Python VM (a copy of swarmvm's runtime): the VM, its image reader and step writer, the "
                         "apps' options and loop, the robot adapters (real and simulated)"),
        ("{name}.svm", "the table image"),
        ("README.md", "this file"))))
