"""The footprint sidecar: what ``swarmvm footprint`` needs to know of a generated project's image
and cannot read from it, written by gen beside the ELF (docs/footprint.md, "Sidecars").

gen writes the program around the VM, so it knows what that program calls through pointers (the
declarations of the target's record, ``--indirect``'s form), which events a script may name, and
which table image it compiles in. ``<name>.footprint.json`` carries those from gen to the ELF: the
generated Kilobot Makefile builds ``<name>.elf`` in the folder that holds it, the CapBot
CMakeLists.txt copies it beside the ``zephyr.elf`` it builds. ``swarmvm footprint X.elf`` reads
``X.footprint.json`` when there is one, so a generated project needs no ``--indirect``; its event
script (what ``swarmvm script --steps N --seed 1`` prints) is run by ``--cycles X.footprint.json``.

It fails closed: a sidecar is the statement of one table image's build, so one beside an ELF of
another image (its ``tables_sha256`` is not the ELF's), of another target, or that is not this
format is refused (InputError naming the file and the key), never read in part or passed over.
This module names no target: the records give what it holds (swarmvm.targets.generate)."""

import hashlib
import json
import os
from collections.abc import Sequence
from dataclasses import dataclass

from ..boundary.errors import InputError
from ..boundary.structure import read_json_document
from ..compiler.tables import Tables
from ..readers.event_script import random_rows, script_lines

FORMAT_NAME = "swarmvm footprint sidecar"
VERSION = 1
SUFFIX = ".footprint.json"
SCRIPT_SEED = 1             # the seed of the script gen writes: the recipes' `swarmvm script --seed 1`
MAX_BYTES = 1 << 20         # a script of 40 steps of a 255-event model is well under it
KEYS = ("format", "version", "target", "tables_sha256", "indirect", "script")


@dataclass(frozen=True)
class Sidecar:
    """A sidecar as read: its path, the target and table image it was written for, its
    ``--indirect`` declarations (parsed where they are used, swarmvm.footprint.stack.parse_indirect,
    which names this file when one is not of that form) and its event script's lines."""
    path: str
    target: str
    tables_sha256: str
    indirect: tuple[str, ...]
    script: tuple[str, ...]

    @property
    def script_text(self) -> str:
        """The script as ``swarmvm script`` prints it: the same bytes, so the same digest."""
        return "".join(line + "\n" for line in self.script)

    @property
    def script_sha256(self) -> str:
        return hashlib.sha256(self.script_text.encode("utf-8")).hexdigest()


def sidecar_text(target: str, image: bytes, tables: Tables, events: Sequence[str], indirect: Sequence[str],
                 steps: int) -> str:
    """The sidecar gen writes for an image of ``target`` compiling in ``image``: its digest, the
    target's ``indirect`` declarations, and a reproducible event script of ``steps`` steps over
    the model's ``events`` (seed SCRIPT_SEED). JSON, keys sorted: the same model, the same bytes."""
    script = list(script_lines(random_rows(tables, steps, SCRIPT_SEED), events))
    data = dict(format=FORMAT_NAME, version=VERSION, target=target, tables_sha256=hashlib.sha256(image).hexdigest(),
                indirect=list(indirect), script=script)
    return json.dumps(data, indent=2, sort_keys=True) + "\n"


def sidecar_path(elf: str) -> str:
    """Where the sidecar of ``elf`` is: beside it, its name with ``.elf`` replaced by SUFFIX."""
    stem, extension = os.path.splitext(elf)
    return (stem if extension == ".elf" else elf) + SUFFIX


def _strings(path: str, key: str, value: object) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise InputError(path, key, "must be a list of strings")
    return tuple(value)


def read_sidecar(path: str) -> Sidecar:
    """The sidecar in the file ``path``; InputError naming the file and the key for anything that
    is not a sidecar of this format version."""
    data = read_json_document(path, FORMAT_NAME, VERSION, "footprint sidecar", "write it again with swarmvm gen",
                              limit=MAX_BYTES)
    unknown = sorted(set(data) - set(KEYS))
    if unknown:
        raise InputError(path, unknown[0], "unknown key (a sidecar has %s)" % ", ".join(KEYS))
    for key in ("target", "tables_sha256"):
        if not isinstance(data.get(key), str):
            raise InputError(path, key, "must be a string")
    return Sidecar(path, data["target"], data["tables_sha256"], _strings(path, "indirect", data.get("indirect")),
                   _strings(path, "script", data.get("script")))


def checked(sidecar: Sidecar, elf: str, target: str, tables_sha256: str | None) -> Sidecar:
    """``sidecar`` when it was written for the image of ``elf`` (of ``target``, its table image's
    digest ``tables_sha256``); InputError naming what differs otherwise."""
    if sidecar.target != target:
        raise InputError(sidecar.path, "target", "a sidecar of a %s image, but %s is a %s image: it is not this "
                         "image's (run swarmvm gen and the build again)" % (sidecar.target, elf, target))
    if sidecar.tables_sha256 != tables_sha256:
        raise InputError(sidecar.path, "tables_sha256", "%s... is not the digest of the table image in %s (%s...): "
                         "the sidecar of another supervisor's build (run swarmvm gen and the build again)"
                         % (sidecar.tables_sha256[:12], elf, (tables_sha256 or "none")[:12]))
    return sidecar


def sidecar_of(elf: str, target: str, tables_sha256: str | None) -> Sidecar | None:
    """The sidecar beside ``elf``, checked against its image (:func:`checked`); None when there
    is no file there."""
    path = sidecar_path(elf)
    if not os.path.lexists(path):
        return None
    return checked(read_sidecar(path), elf, target, tables_sha256)
