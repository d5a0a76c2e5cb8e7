"""The readers of every input format, one module per format named for it.

A one-automaton file (one local supervisor) is read by the reader its suffix names in
:data:`READERS`; a directory or a list of them is assembled into a supervisor set by
:mod:`.automata`. A compiled supervisor set is Nadzoru 2's ``supervisor.yaml``
(:mod:`.supervisor_yaml`). Event scripts and synthesis scripts have a reader each too."""

import os
from collections.abc import Callable

from ..boundary.errors import InputError
from .automaton import AutomatonFile
from .faudes_gen import read_gen
from .ides_xmd import read_xmd
from .nadzoru_nza import read_nza
from .nadzoru_xml import read_nadzoru_xml

# Suffix (lower case) -> the reader of a one-automaton file of that format.
READERS: dict[str, Callable[[str], AutomatonFile]] = {
    ".xml": read_nadzoru_xml,   # Nadzoru 2
    ".xmd": read_xmd,           # IDES 2.x
    ".nza": read_nza,           # Nadzoru (Lua literal)
    ".gen": read_gen,           # libFAUDES token format
}
SUFFIXES = tuple(READERS)


def read_automaton(path: str) -> AutomatonFile:
    """Any one-automaton file, by its suffix -> :class:`~swarmvm.readers.automaton.AutomatonFile`."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in READERS:
        raise InputError(path, "", "not an automaton file (%s)" % ", ".join(SUFFIXES))
    return READERS[suffix](path)
