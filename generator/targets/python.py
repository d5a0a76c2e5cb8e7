"""The python target (templates/python/, docs/robots/python.md): the table module, an app
binding the callbacks and the Python VM, standard library only."""

from ..compiler.runtime_files import (
    RUNTIME_FORMAT_PY,
    RUNTIME_LEARN_PY,
    RUNTIME_PY,
    RUNTIME_PY_DIR,
    RUNTIME_STEP_PY,
    TEMPLATES,
)
from .record import Readme, Target

# The Python VM, the image format it reads and its step writer (swarmvm_vm imports swarmvm_format
# and swarmvm_step_source), and what the apps (python3 -m <name>_app) share: their options and
# fixed-rate loop. The Pi-puck ships them too.
PY_RUNTIME_COPIES = ((RUNTIME_PY, "swarmvm_vm.py"), (RUNTIME_FORMAT_PY, "swarmvm_format.py"),
                     (RUNTIME_STEP_PY, "swarmvm_step_source.py"),
                     (RUNTIME_PY_DIR / "swarmvm_app.py", "swarmvm_app.py"))

TARGET = Target(
    "python",
    "Python VM: table module, app module binding the callbacks, controller skeleton, the runtime (stdlib only)",
    templates=(("python/tables.py.j2", "{name}_tables.py", False),
               ("python/app.py.j2", "{name}_app.py", False),
               ("python/controller.py.j2", "{name}_controller.py", True)),
    template_folder=TEMPLATES / "python",
    page="robots/python.md",
    copies=PY_RUNTIME_COPIES,
    learned_templates=(("python/learned.py.j2", "{name}_learned.py", False),),
    learned_copies=((RUNTIME_LEARN_PY, "swarmvm_learn.py"),),
    keeps_order=True,
    readme=Readme("python/readme.md.j2", (
        ("{name}_tables.py", "the table image as bytes, and the event names"),
        ("{name}_app.py", "make_vm() and the fixed-rate main: python3 -m {name}_app"),
        ("{name}_controller.py", "a Controller with one on_EVENT per event and one check_EVENT per uncontrollable "
                                 "event"),
        ("{name}_learned.py", "the learned checks of --learned-check"),
        ("swarmvm_*.py", "the Python VM (a copy of swarmvm's runtime): the VM, the image format, its step writer, the "
                         "apps' options and fixed-rate loop (and with --learned-check the learned policy)"),
        ("{name}.svm", "the table image"),
        ("README.md", "this file"))))
