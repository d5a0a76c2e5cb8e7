"""What the C-family targets' build files and glue are told, decided once here, not in templates.

The C runtime ships as groups of files (a header and its source); a target copies some groups
(swarmvm.targets) and its build file compiles some of them, and both lists come from
:data:`RUNTIME_GROUPS`. The VM features a generated program compiles in (swarmvm.h's
``SVM_WITH_*``) follow from what the generated code calls, decided by :func:`features` for
every target that sets them. A Kilobot message's payload is cut to the 9 bytes kilolib carries
here too. Templates only write these values out."""

from collections.abc import Mapping

from ..compiler.naming import KILOBOT_MESSAGE_BYTES, event_names
from ..compiler.pipeline import Compiled

# The C runtime's files by the part they implement, each in the order builds list them.
RUNTIME_GROUPS: Mapping[str, tuple[str, ...]] = {
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

# swarmvm.h's features (SVM_WITH_<name>), in the order it declares them.
FEATURES = ("BINDINGS", "NAMES", "FIRST", "WEIGHTED", "LEARNED")


def runtime_files(*groups: str) -> tuple[str, ...]:
    """The files of ``groups``, in that order."""
    return tuple(name for group in groups for name in RUNTIME_GROUPS[group])


def sources(*groups: str) -> list[str]:
    """The C sources of ``groups``, by stem (a template writes ``<stem>.c``): what a build compiles."""
    return [name[:-len(".c")] for name in runtime_files(*groups) if name.endswith(".c")]


def headers(*groups: str) -> list[str]:
    """The headers of ``groups``, by stem: what a build's rule depends on besides its sources."""
    return [name[:-len(".h")] for name in runtime_files(*groups) if name.endswith(".h")]


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


def c_values(compiled: Compiled) -> dict[str, object]:
    """The c target's Makefile: the runtime it compiles (the core and Nadzoru's C API)."""
    return dict(runtime_sources=sources("core", "sct"), runtime_headers=headers("core", "sct"))


def kilobot_values(compiled: Compiled) -> dict[str, object]:
    """The Kilobot target: the runtime its Makefile compiles (more with ``STREAM=1`` and
    ``LEARNED=1``), the features of each build (the streaming one matches a received image's
    events by name), and each public event's message payload (event index -> the first
    KILOBOT_MESSAGE_BYTES characters of its message name)."""
    probabilistic = compiled.tables.probs is not None
    return dict(runtime_sources=sources("core", "kilobot"), runtime_headers=headers("core", "kilobot"),
                stream_sources=sources("stream"), learned_sources=sources("learn"),
                features=features(probabilistic, names=False), stream_features=features(probabilistic, names=True),
                payloads={e.index: e.message[:KILOBOT_MESSAGE_BYTES]
                          for e in event_names(compiled.model) if e.message is not None})


def capbot_values(compiled: Compiled) -> dict[str, object]:
    """The CapBot's CMakeLists.txt: the runtime it compiles (more with ``SVM_LEARNED``, the store
    on Zephyr's flash last) and its features (main.c matches the logic page's events by name)."""
    return dict(runtime_sources=sources("core", "logic_page"), learned_sources=sources("learn"),
                store_sources=sources("store_zephyr"), features=features(compiled.tables.probs is not None, names=True))
