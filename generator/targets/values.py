"""What the C-family targets (c, kilobot, capbot) share in their build files and glue, decided
once here, not in templates.

The C runtime ships as groups of files (a header and its source); a target copies some groups
(:func:`c_copies`, in its record) and its build file compiles some of them, and both lists come
from :data:`RUNTIME_GROUPS`. The VM features a generated program compiles in (swarmvm.h's
``SVM_WITH_*``) follow from what the generated code calls, decided by :func:`features` for
every target that sets them. Templates only write these values out."""

from collections.abc import Mapping

from ..compiler.runtime_files import RUNTIME_C
from ..compiler.tables import Tables
from .record import RuntimeCopy

# The C runtime's files by the part they implement, each in the order builds list them.
RUNTIME_GROUPS: Mapping[str, tuple[str, ...]] = {
    # what swarmvm.h and swarmvm.c include, written by scripts/format_headers.py: the format's
    # numbers, and the host build's checksum tables
    "format": ("swarmvm_format.h", "swarmvm_crc_tables.h"),
    "core": ("swarmvm.h", "swarmvm.c"),
    "sct": ("swarmvm_sct.h", "swarmvm_sct.c"),                     # Nadzoru 2's C API
    "trace": ("swarmvm_trace.h",),
    "logic_page": ("swarmvm_logic_page.h", "swarmvm_logic_page.c"),
    "stream": ("swarmvm_stream.h", "swarmvm_stream.c"),
    "kilobot": ("swarmvm_kilobot.h", "swarmvm_kilobot.c"),
    "kilobot_eeprom": ("swarmvm_kilobot_eeprom.h",),
    # the learned selection policy kept in a power-cut-safe store (docs/learning.md)
    "learn": ("swarmvm_learn.h", "swarmvm_learn.c", "swarmvm_learn_store.h", "swarmvm_learn_store.c",
              "swarmvm_store.h", "swarmvm_store.c"),
    "store_zephyr": ("swarmvm_store_zephyr.h", "swarmvm_store_zephyr.c"),
}

# What every C target ships: the VM (with the format headers it includes), Nadzoru 2's C API over
# it, the canonical trace line.
C_RUNTIME_GROUPS = ("format", "core", "sct", "trace")

# swarmvm.h's features (SVM_WITH_<name>), in the order it declares them.
FEATURES = ("BINDINGS", "NAMES", "FIRST", "WEIGHTED", "LEARNED")


def runtime_files(*groups: str) -> tuple[str, ...]:
    """The files of ``groups``, in that order."""
    return tuple(name for group in groups for name in RUNTIME_GROUPS[group])


def c_copies(*groups: str, folder: str = "") -> tuple[RuntimeCopy, ...]:
    """The C runtime's files of ``groups`` as a target's copies into ``folder``."""
    return tuple((RUNTIME_C / n, folder + n) for n in runtime_files(*groups))


def sources(*groups: str) -> list[str]:
    """The C sources of ``groups``, by stem (a template writes ``<stem>.c``): what a build compiles."""
    return [name[:-len(".c")] for name in runtime_files(*groups) if name.endswith(".c")]


def headers(*groups: str) -> list[str]:
    """The headers of ``groups``, by stem: what a build's rule depends on besides its sources."""
    return [name[:-len(".h")] for name in runtime_files(*groups) if name.endswith(".h")]


def has_public_inputs(tables: Tables) -> bool:
    """Whether the model has a public uncontrollable event: the only events the step's
    public-first pass polls and applies first (a public controllable event is chosen as any
    other), so a model without one needs no pass (``SVM_WITH_PUBLIC=0``, whose load refuses an
    image with one)."""
    return bool(tables.public & ~tables.controllable)


def minimal_features(public_inputs: bool) -> list[tuple[str, int]]:
    """The features the minimal flash profile (swarmvm.h's SVM_TRUSTED_IMAGE) leaves out of a
    generated program because of its model: the step's public-first pass when the model has no
    public uncontrollable event (``public_inputs`` false). (Whether the violation counter goes
    too depends on the user's controller, which the build reads: templates/kilobot/Makefile.j2.)"""
    return [] if public_inputs else [("PUBLIC", 0)]


def features(probabilistic: bool, names: bool) -> list[tuple[str, int]]:
    """The (feature, 0 or 1) a generated program sets, ``-DSVM_WITH_<feature>=<value>`` in its
    build (c/_macros.j2's feature_flags): its callbacks go through the generated
    dispatch (no binding table) and its options are set in code, so of the policies only
    ``weighted`` is compiled in, when the model has probabilities (``learned`` is the build's
    option, turned on by its own flag). ``names``: the program reads event names, so the feature
    is left to swarmvm.h's default (on); otherwise it is left out."""
    chosen = dict(BINDINGS=0, FIRST=0, WEIGHTED=int(probabilistic), LEARNED=0)
    if not names:
        chosen["NAMES"] = 0
    return [(feature, chosen[feature]) for feature in FEATURES if feature in chosen]
