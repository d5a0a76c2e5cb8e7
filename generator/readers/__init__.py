"""The readers of every input format, one module per format named for it.

A one-automaton file (one local supervisor) is read by the reader its suffix names in
:data:`READERS`; a directory or a list of them is assembled into a supervisor set by
:mod:`.automata`. A compiled supervisor set, one file, is read by the reader its suffix names in
:data:`SUPERVISOR_READERS`: Nadzoru 2's ``supervisor.yaml`` (:mod:`.supervisor_yaml`) or the C
tables of Nadzoru's generic C VM (:mod:`.nadzoru_c`). Event scripts and synthesis scripts have a
reader each too."""

import os
from collections.abc import Callable

from ..boundary.errors import InputError
from ..compiler.model import Supervisors
from .automaton import AutomatonFile
from .faudes_gen import read_gen
from .ides_xmd import read_xmd
from .nadzoru_c import read_nadzoru_c
from .nadzoru_nza import read_nza
from .nadzoru_xml import read_nadzoru_xml
from .supervisor_yaml import load_supervisor
from .svm_image import read_svm

# Suffix (lower case) -> the reader of a one-automaton file of that format.
READERS: dict[str, Callable[[str], AutomatonFile]] = {
    ".xml": read_nadzoru_xml,   # Nadzoru 2
    ".xmd": read_xmd,           # IDES 2.x
    ".nza": read_nza,           # Nadzoru (Lua literal)
    ".gen": read_gen,           # libFAUDES token format
}

# Suffix (lower case) -> the reader of a compiled supervisor set of that format; the reader
# takes the file and ``published`` (read as the published VMs read it: docs/compat.md).
SUPERVISOR_READERS: dict[str, Callable[[str, bool], Supervisors]] = {
    ".yaml": load_supervisor,   # Nadzoru 2's supervisor.yaml
    ".yml": load_supervisor,
    ".c": read_nadzoru_c,       # the tables of Nadzoru's generic C VM (a source or a header)
    ".h": read_nadzoru_c,
    ".svm": read_svm,           # a table image, read back as the set it was packed from
}


def kinds() -> str:
    """What swarmvm reads, for a message refusing a file of no known kind."""
    return "a supervisor (%s) or automata (%s)" % (", ".join(SUPERVISOR_READERS), ", ".join(READERS))


def read_supervisor(path: str, published: bool = False) -> Supervisors:
    """A compiled supervisor set, by its suffix; a file of no known kind refused in one line
    that names the kinds swarmvm reads."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in SUPERVISOR_READERS:
        raise InputError(path, "", "not a file swarmvm reads (%s)" % kinds())
    return SUPERVISOR_READERS[suffix](path, published)


def read_automaton(path: str) -> AutomatonFile:
    """Any one-automaton file, by its suffix -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in READERS:
        raise InputError(path, "", "not an automaton file (%s)" % ", ".join(READERS))
    return READERS[suffix](path)
