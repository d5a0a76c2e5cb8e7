"""The files a target creates once for the user to edit (controller skeletons), kept over later
``swarmvm gen`` runs, and checked against the model each time.

A kept file does not change when the model does. Instead of leaving it silently stale, ``gen``
compares the callbacks it defines with the ones a fresh skeleton defines (the same naming rule
made both, generator/compiler/naming.py) and says which are missing or stale; the fresh skeleton is written
beside it as ``<file>.new`` to copy from."""

import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from ..boundary.errors import read_input


def _callback_pattern(rel: str, model: str) -> re.Pattern[str]:
    """Callback names in a user file, by its language (compiler/naming.py's spellings)."""
    if rel.endswith(".py"):
        return re.compile(r"^\s*def ((?:check|on)_\w*)\s*\(", re.M)
    if rel.endswith((".cpp", ".h", ".hpp")):
        return re.compile(r"\b((?:Check|On)_\w*)\s*\(")
    return re.compile(r"\b(%s_(?:check|on)_\w*)\s*\(" % re.escape(model))


@dataclass(frozen=True)
class Drift:
    """How a kept user file differs from a fresh skeleton."""
    path: str
    missing: tuple[str, ...]
    stale: tuple[str, ...]

    def message(self) -> str:
        parts = []
        if self.missing:
            parts.append("callbacks missing (events the model has): " + ", ".join(self.missing))
        if self.stale:
            parts.append("stale callbacks (events the model no longer has): " + ", ".join(self.stale))
        return "%s: %s; kept as it is, a fresh skeleton is %s.new" % (self.path, "; ".join(parts), self.path)


def drift(path: Path, fresh: bytes, model: str, generated: Iterable[bytes] = ()) -> Drift | None:
    """The difference between the kept file at ``path`` and the ``fresh`` skeleton, if any.
    Callbacks the ``generated`` files of the same run define (such as the ARGoS base class's
    message defaults, which a user may override) are not stale."""
    pattern = _callback_pattern(path.name, model)
    wanted = set(pattern.findall(fresh.decode("utf-8")))
    defined = wanted.union(*(pattern.findall(data.decode("utf-8", errors="replace")) for data in generated))
    # the user's file, through the input layer: a FIFO or a device in its place is refused, not waited on
    present = set(pattern.findall(read_input(str(path)).decode("utf-8", errors="replace")))
    missing, stale = wanted - present, present - defined
    if not missing and not stale:
        return None
    return Drift(str(path), tuple(sorted(missing)), tuple(sorted(stale)))
