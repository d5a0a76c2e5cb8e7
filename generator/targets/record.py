"""What a target is, in one record: everything the compiler, footprint and the tests know of it.

Each module ``swarmvm.targets.<name>`` exports one :class:`Target` as ``TARGET`` (the registry,
swarmvm.targets, collects them), with its templates (one folder, ``templates/<name>/``, and any
shared ones it reuses), the runtime files it copies, the values and naming rules its templates
need, and, for a robot whose linked images swarmvm measures, its limits, how its ELF files are
recognised and how an image is built. Nothing else in the package names a target: a new one is
that module, its template folder and its docs page (docs/extending.md)."""

from collections.abc import Callable
from dataclasses import dataclass, field
from importlib.abc import Traversable

from ..compiler.pipeline import Compiled

TemplateFile = tuple[str, str, bool]        # (template, output name, keep)
RuntimeCopy = tuple[Traversable, str]       # (source path, output name)
TemplateValues = Callable[[Compiled], dict[str, object]]


@dataclass(frozen=True)
class RobotLimits:
    """A robot's hard limits, checked on every footprint row of its target (swarmvm.footprint.budget):
    flash an image may use, the SRAM, and the part of it static RAM must leave to the stack."""
    robot: str                  # the robot as the checks' messages name it ("Kilobot")
    flash: int
    sram: int
    min_stack: int


@dataclass(frozen=True)
class Elf:
    """How swarmvm.footprint recognises and reads the target's linked images.

    An ELF is the target's when its ``e_machine`` is ``machine`` and it defines every symbol of
    ``symbols``; of several targets that match, the one that asks for the most symbols wins, so a
    second target of a machine tells itself apart by a symbol only its runtime defines (a first
    one may ask for none). ``architecture`` names the instruction reader of the worst-case stack
    (swarmvm.footprint.stack.ARCHITECTURES), ``emulator`` what runs an image for cycles per step
    (swarmvm.footprint.cycles.EMULATORS), None when nothing does. ``make_rule`` is the project's
    make target that builds a corpus supervisor's image (mk/<target>.mk), as the tests build them;
    ``platform_runtime`` the runtime sources that run the VM as a robot's program (counted as
    application by the footprint, not as VM core); ``indirect`` what the indirect calls of the
    generated program reach (its runtime's and platform library's), so that a generated project
    needs no ``--indirect`` of its own: gen writes that code, so it knows them."""
    machine: str
    architecture: str | None = None
    emulator: str | None = None
    symbols: tuple[str, ...] = ()
    make_rule: str | None = None            # {build}: the BUILD folder, {name}: the supervisor
    platform_runtime: tuple[str, ...] = ()  # its runtime_c/ sources around the VM: application, not VM core
    # What the indirect calls of an image built from the generated project reach (--indirect's
    # CALLER=TARGET,... form): footprint's stack and cycles use them, with the user's own added.
    indirect: tuple[str, ...] = ()
    # What gen writes into the footprint sidecar of the generated project (swarmvm.footprint.sidecar),
    # for the images built from it and no other: the declarations of its builds beyond ``indirect``
    # (a target whose images come from several builds states each build's in its sidecar), and
    # the steps of the event script, no more than an image of the target runs.
    generated_indirect: tuple[str, ...] = ()
    script_steps: int = 40


@dataclass(frozen=True)
class Readme:
    """What the README.md gen writes into every generated folder says of this target (one
    template for all, templates/common/README.md.j2): ``part`` names the target's template of
    macros ``build()`` and ``run()``, its commands in its own words; ``files`` says what each
    file gen writes is, as (pattern of output names, fnmatch, with {name}; what it is), the
    first pattern that matches a file describing it: every file gen writes matches one, so the
    README lists them all (tests/targets/test_readme.py)."""
    part: str
    files: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class Target:
    """One target of ``swarmvm gen --target``. Output names may use ``{name}``; ``keep`` marks
    user-edited files that are never overwritten."""
    name: str
    description: str
    templates: tuple[TemplateFile, ...]
    template_folder: Traversable            # its own templates: the "<name>/..." template names
    page: str                               # its docs page: robots/<name>.md in the checkout's docs, or a full path
    copies: tuple[RuntimeCopy, ...] = field(default=())
    learned_templates: tuple[TemplateFile, ...] = field(default=())   # added by --learned-check (docs/learning.md)
    learned_copies: tuple[RuntimeCopy, ...] = field(default=())
    rules: TemplateValues | None = None     # its own naming rules: extra template values; InputError if unfit
    values: TemplateValues | None = None    # template values decided in Python
    keeps_order: bool = False               # its image keeps the source order (the Python SCT's exact mode)
    build: tuple[str, ...] = ()             # the command that builds the generated folder in place ({name})
    limits: RobotLimits | None = None       # a robot's hard limits (footprint checks)
    elf: Elf | None = None                  # its linked images, when footprint measures them
    readme: Readme | None = None            # what its folder's README.md says of it
