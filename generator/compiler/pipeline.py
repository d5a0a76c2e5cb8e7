"""The compiler pipeline in one call: load -> validate -> canonicalise -> tables -> image."""

import functools
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Optional

from ..boundary.errors import InputError, note_read
from ..readers import READERS, read_supervisor
from ..readers.automata import load_automata
from .canonical import canonicalise
from .image import pack
from .model import Model, Supervisors
from .naming import default_stem, model_identifier
from .runtime_files import image_format
from .tables import Tables, build_tables


@dataclass(frozen=True)
class Compiled:
    stem: str          # the name asked for (--name), else the first input's file stem
    source: str        # the first input, which an error about the name names
    model: Model
    tables: Tables
    image: bytes
    # The image with the order section too when the input is a supervisor.yaml (its event order
    # and state numbers, for the Python compatibility API's exact mode: docs/compat.md), else
    # the image itself. The Python targets ship it; the VMs do not need it.
    ordered_image: bytes = b""
    # What `swarmvm pack` writes: from a supervisor.yaml, the ordered image with the source
    # section too (the file's digest, its current states, its names as written: docs/compat.md),
    # else the ordered image.
    packed_image: bytes = b""

    @functools.cached_property
    def name(self) -> str:
        """The identifier-safe model name (naming.model_identifier) of generated identifiers and
        file names; InputError (key --name) for a reserved or overlong one. Checked where code
        or files are named after the model, not when compiling: check, pack, script and equiv
        name nothing after it, so a supervisor in a file called new.yaml is fine there."""
        return model_identifier(self.stem, self.source)


def expand_directories(paths: Sequence[str]) -> list[str]:
    """Each directory among ``paths`` replaced by the automaton files in it, in natural order
    (``x_2.gen`` before ``x_10.gen``): ``swarmvm export --format gen`` writes a set that way.
    Each is recorded as read, as its files are."""
    out = []
    for path in paths:
        if not os.path.isdir(path):
            out.append(path)
            continue
        found = [os.path.join(path, f) for f in os.listdir(path) if os.path.splitext(f)[1].lower() in READERS]
        if not found:
            raise InputError(path, "", "directory holds no automata (%s)" % ", ".join(READERS))
        note_read(os.stat(path))       # no output may be written into a folder being read
        out.extend(sorted(found, key=lambda f: [int(p) if p.isdecimal() else p for p in re.split(r"(\d+)", f)]))
    return out


def load(paths: Sequence[str]) -> Supervisors:
    """One supervisor file (a reader of readers.SUPERVISOR_READERS: supervisor.yaml, Nadzoru's
    C tables, a .svm image), or one or more automata (readers.READERS; one local supervisor
    each, chosen by suffix; a directory stands for the automata in it)."""
    return load_as(paths, published=False)


def load_as(paths: Sequence[str], published: bool) -> Supervisors:
    """:func:`load`; ``published``: a supervisor file read as the published VMs read it
    (readers.supervisor_yaml)."""
    paths = expand_directories(paths)
    automata = [p for p in paths if os.path.splitext(p)[1].lower() in READERS]
    if automata and len(automata) != len(paths):
        raise InputError(paths[0], "", "give either one supervisor file or automata (%s), not both" % ", ".join(READERS))
    if not automata and len(paths) != 1:
        raise InputError(paths[1], "", "a compiled supervisor is one file; give one at a time")
    spec: Supervisors = load_automata(paths) if automata else read_supervisor(paths[0], published)
    return spec


def compile_inputs(paths: Sequence[str], name: Optional[str] = None, names: bool = True,
                   published: bool = False) -> Compiled:
    """Run the whole pipeline; raises InputError on bad input. ``published``: a supervisor.yaml
    is read as the published VMs read it (load_supervisor)."""
    return compile_spec(load_as(paths, published), paths, name, names)


def compile_spec(spec: Supervisors, paths: Sequence[str], name: Optional[str] = None, names: bool = True) -> Compiled:
    """The pipeline after loading: canonicalise, build tables, pack the image (and the image
    with the source order, see :class:`Compiled`)."""
    model = canonicalise(spec)
    tables = build_tables(model)
    image = pack(tables, spec.source, names=names)
    ordered = packed = image
    if names and spec.file_order:
        positions = [spec.events.index(event) for event in model.events]
        order = (positions, [number for sup in model.supervisors for number in sup.input_states])
        ordered = pack(tables, spec.source, names=True, order=order)
        # (A written name over the format's MAX_NAME_LENGTH bytes, `EV_` and a name filling the
        # rest, leaves the source section out: exact mode then names events EV_<name>, as written.)
        fits = spec.digest and all(len(name) <= image_format().MAX_NAME_LENGTH for name in spec.written)
        packed = ordered if not fits else pack(tables, spec.source, names=True, order=order, source_section=(
            spec.digest, [sup.start for sup in model.supervisors], [spec.written[i] for i in positions]))
    stem = name or default_stem(paths[0])
    return Compiled(stem, paths[0], model, tables, image, ordered, packed)
