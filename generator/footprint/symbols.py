"""What a reviewer needs of an image beyond its figures (docs/footprint.md, "JSON", "Symbols"):
its section and symbol sizes, read from the linked ELF, so that a later run can say which
sections and symbols changed (``--symbols N``, as Bloaty's ``-d sections,symbols`` does); the
commit of the work tree holding it; the toolchain that built it.

Nothing here is guessed. The sizes are read from the same bytes the figures were measured from
(the ELF's digest must be the one measured; a file that changed in between is refused), through
the input layer and measure.py's own section and symbol readers, so the sections and symbols
sum to the same totals. A commit is recorded only when ``git`` names one for the ELF's folder,
else null with git's reason; the toolchain is the ELF's ``.comment`` (what built the image), else
the installed cross compiler's ``--version``, marked as such, else null with why."""

import hashlib
import io
import os
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from elftools.common.exceptions import ELFError
from elftools.elf.elffile import ELFFile

from ..boundary.errors import ELF_MAX_BYTES, InputError, read_input
from .measure import Footprint, FootprintError, _check_symbol, _memory_kind, _symbols
from .stack import StackUnknown, architecture

UNATTRIBUTED = "[section %s]"       # a section's bytes no symbol accounts for, named as Bloaty does
TOOL_TIMEOUT = 30                    # seconds git or a compiler's --version may take before it counts as no answer


@dataclass(frozen=True)
class Section:
    """One memory section of a linked image: its kind (measure's ``flash``, ``ram``, ``both``), its
    size, and the sizes of the symbols in it, the bytes no symbol covers as ``[section NAME]``."""
    kind: str
    size: int
    symbols: dict[str, int]

    def as_json(self) -> dict[str, Any]:
        return dict(kind=self.kind, size=self.size, symbols=dict(sorted(self.symbols.items())))


@dataclass(frozen=True)
class Commit:
    """The commit of the work tree holding an ELF (``sha``), whether tracked files differ from it
    (``modified``: the image may then be of changes not in it), or None and ``why``."""
    sha: str | None
    modified: bool = False
    why: str = ""

    def as_json(self) -> dict[str, Any]:
        return dict(sha=self.sha, modified=self.modified) if self.sha else dict(sha=None, why=self.why)

    def text(self) -> str:
        if self.sha is None:
            return "unknown (%s)" % self.why
        return self.sha[:12] + (" (modified)" if self.modified else "")


@dataclass(frozen=True)
class Toolchain:
    """The compilers of an image and where that was read (``.comment``, or an installed
    compiler's ``--version``), or none and ``why``."""
    versions: tuple[str, ...]
    source: str | None
    why: str = ""

    def as_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {"versions": list(self.versions), "from": self.source}
        return dict(data, why=self.why) if self.why else data

    def text(self) -> str:
        if not self.versions:
            return "unknown (%s)" % self.why
        return "; ".join(self.versions) + ("" if self.source == ".comment" else " (from %s)" % self.source)


@dataclass(frozen=True)
class ImageFacts:
    """What the JSON records of an image besides its figures; ``sections`` None when a baseline
    written by an older swarmvm holds none."""
    sections: dict[str, Section] | None
    commit: Commit | None = None
    toolchain: Toolchain | None = None
    elf: str = ""
    elf_sha256: str | None = None

    def as_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {}
        if self.commit is not None:
            data["commit"] = self.commit.as_json()
        if self.toolchain is not None:
            data["toolchain"] = self.toolchain.as_json()
        if self.sections is not None:
            data["sections"] = {name: s.as_json() for name, s in sorted(self.sections.items())}
        return data


def read_sections(path: str, elf_sha256: str | None = None) -> dict[str, Section]:
    """The memory sections of a linked ELF with their symbols' sizes (aliases once, a static
    symbol named with its source file: ``load (swarmvm.c)``). ``elf_sha256``: the digest the
    caller measured; FootprintError when the file no longer has it."""
    data = read_input(path, limit=ELF_MAX_BYTES)
    if elf_sha256 is not None and hashlib.sha256(data).hexdigest() != elf_sha256:
        raise FootprintError("%s: changed while it was read (its sha256 is no longer the one measured)" % path)
    try:
        elf = ELFFile(io.BytesIO(data))
        kinds = {index: _memory_kind(s) for index, s in enumerate(elf.iter_sections())}
        sections: dict[str, tuple[str, int, dict[str, int]]] = {
            elf.get_section(i).name: (kind, elf.get_section(i)["sh_size"], {}) for i, kind in kinds.items() if kind is not None}
        for symbol, local_file in _symbols(elf):
            _check_symbol(path, elf, symbol)
            kind = kinds[symbol["st_shndx"]]
            if kind is None:
                continue
            name = symbol.name if local_file is None else "%s (%s)" % (symbol.name, local_file)      # escaped: json.dumps, markdown() in the report
            symbols: dict[str, int] = sections[elf.get_section(symbol["st_shndx"]).name][2]
            symbols[name] = symbols.get(name, 0) + symbol["st_size"]
    except ELFError as exc:
        raise FootprintError("%s: not an ELF image (%s)" % (path, exc))
    result = {}
    for name, (kind, size, symbols) in sections.items():
        rest = size - sum(symbols.values())
        if rest > 0:                     # (symbols overlapping each other leave none)
            symbols[UNATTRIBUTED % name] = rest
        result[name] = Section(kind, size, symbols)
    return result


def _git(folder: Path, *words: str) -> subprocess.CompletedProcess[str]:
    """git run on ``folder`` alone: the caller's GIT_DIR or GIT_WORK_TREE would name another tree."""
    env = {k: v for k, v in os.environ.items() if k not in ("GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE")}
    return subprocess.run(["git", "-C", str(folder), *words], capture_output=True, text=True, timeout=TOOL_TIMEOUT,
                          env=env)


def commit_of(path: str) -> Commit:
    """``git rev-parse HEAD`` of the folder holding ``path``, or None and git's reason."""
    if shutil.which("git") is None:
        return Commit(None, why="git not found")
    folder = Path(path).absolute().parent
    try:
        inside = _git(folder, "rev-parse", "--is-inside-work-tree")
        if inside.returncode != 0 or inside.stdout.strip() != "true":
            return Commit(None, why="%s is not in a git work tree" % folder)      # escaped: json.dumps, markdown() in the report
        head = _git(folder, "rev-parse", "--verify", "--quiet", "HEAD")
        if head.returncode != 0:
            return Commit(None, why="the git work tree of %s has no commit yet" % folder)      # escaped: json.dumps, markdown() in the report
        status = _git(folder, "status", "--porcelain", "--untracked-files=no")
    except subprocess.TimeoutExpired:
        return Commit(None, why="git did not answer within %d s" % TOOL_TIMEOUT)
    if status.returncode != 0:
        return Commit(None, why="git status failed (%s)" % (status.stderr.strip().splitlines() or [""])[-1])      # escaped: json.dumps, markdown() in the report
    return Commit(head.stdout.strip(), modified=bool(status.stdout.strip()))


def toolchain_of(footprint: Footprint) -> Toolchain:
    """The compilers the ELF's ``.comment`` names (what built it), else the first line of the
    target's installed cross compiler's ``--version`` (which may not be what built it, and says
    so), else none."""
    if footprint.compiler:
        return Toolchain(footprint.compiler, ".comment")
    try:
        compiler = architecture(footprint.target).objdump.removesuffix("objdump") + "gcc"      # escaped: json.dumps, markdown() in the report
    except StackUnknown:
        return Toolchain((), None, "the ELF has no .comment section and no compiler is known for %s" % footprint.target)      # escaped: json.dumps, markdown() in the report
    tool = shutil.which(compiler)
    if tool is None:
        return Toolchain((), None, "the ELF has no .comment section and %s is not installed" % compiler)
    try:
        run = subprocess.run([tool, "--version"], capture_output=True, text=True, timeout=TOOL_TIMEOUT)
    except subprocess.TimeoutExpired:
        return Toolchain((), None, "the ELF has no .comment section and %s --version did not answer" % compiler)
    first = run.stdout.strip().splitlines()[:1]
    if run.returncode != 0 or not first:
        return Toolchain((), None, "the ELF has no .comment section and %s --version failed" % compiler)
    return Toolchain((first[0],), "%s --version (installed; the ELF has no .comment section)" % compiler)


def describe(footprint: Footprint) -> ImageFacts | None:
    """The facts of an image measured from a file (one with a digest); None for a Footprint made
    in memory, which has no file to read them from."""
    if footprint.elf_sha256 is None:
        return None
    return ImageFacts(read_sections(footprint.elf, footprint.elf_sha256), commit_of(footprint.elf),
                      toolchain_of(footprint), footprint.elf, footprint.elf_sha256)


def _at(key: str, *parts: str) -> str:
    """The dotted key of a part of a baseline's image, as its one-line errors name it."""
    return ".".join((key,) + parts)      # escaped: a key of the baseline, in an InputError's message only


def _whole(path: str, key: str, value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise InputError(path, key, "must be a whole number, at least 0")
    return value


def _object(path: str, key: str, value: object) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise InputError(path, key, "must be an object")
    return value


def _sections(path: str, key: str, value: object) -> dict[str, Section]:
    sections = {}
    for name, section in _object(path, key, value).items():
        where = _at(key, name)
        section = _object(path, where, section)
        if section.get("kind") not in ("flash", "ram", "both"):
            raise InputError(path, _at(where, "kind"), "must be flash, ram or both")
        symbols = {symbol: _whole(path, _at(where, "symbols", symbol), size)
                   for symbol, size in _object(path, _at(where, "symbols"), section.get("symbols")).items()}
        sections[name] = Section(section["kind"], _whole(path, _at(where, "size"), section.get("size")), symbols)
    return sections


def _text_list(path: str, key: str, value: object) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise InputError(path, key, "must be a list of strings")
    return tuple(value)


def _optional_text(path: str, key: str, value: object) -> str | None:
    if value is not None and not isinstance(value, str):
        raise InputError(path, key, "must be a string or null")
    return value


def baseline_facts(path: str, key: str, image: dict[str, Any]) -> ImageFacts:
    """The facts a baseline's image records (InputError naming the key of one malformed). A
    baseline without sizes (an older swarmvm's) has them from its ELF when the file it names is
    still there with the digest it records; otherwise ``sections`` is None."""
    commit = toolchain = None
    if "commit" in image:
        data = _object(path, _at(key, "commit"), image["commit"])
        sha = _optional_text(path, _at(key, "commit", "sha"), data.get("sha"))
        commit = Commit(sha, bool(data.get("modified")), _optional_text(path, _at(key, "commit", "why"), data.get("why")) or "")
    if "toolchain" in image:
        data = _object(path, _at(key, "toolchain"), image["toolchain"])
        toolchain = Toolchain(_text_list(path, _at(key, "toolchain", "versions"), data.get("versions")),
                              _optional_text(path, _at(key, "toolchain", "from"), data.get("from")),
                              _optional_text(path, _at(key, "toolchain", "why"), data.get("why")) or "")
    elf = _optional_text(path, _at(key, "elf"), image.get("elf")) or ""
    digest = _optional_text(path, _at(key, "elf_sha256"), image.get("elf_sha256"))
    sections = _sections(path, _at(key, "sections"), image["sections"]) if "sections" in image else None
    return ImageFacts(sections, commit, toolchain, elf, digest)


def sections_of(facts: ImageFacts) -> tuple[dict[str, Section] | None, str]:
    """A baseline image's sections: recorded, else read from the ELF it names when that file is
    still the one measured; else None and why not."""
    if facts.sections is not None:
        return facts.sections, ""
    if not facts.elf or facts.elf_sha256 is None:
        return None, "it records no section or symbol sizes, nor an ELF with its digest"
    if not Path(facts.elf).is_file():
        return None, "it records no section or symbol sizes, and its ELF %s is gone" % facts.elf      # escaped: json.dumps, markdown() in the report
    try:
        return read_sections(facts.elf, facts.elf_sha256), ""
    except FootprintError:
        return None, "it records no section or symbol sizes, and its ELF %s has changed since" % facts.elf      # escaped: json.dumps, markdown() in the report


@dataclass(frozen=True)
class SizeChange:
    """A section's or a symbol's size before and after (None: not in that image)."""
    section: str
    name: str
    old: int | None
    new: int | None

    @property
    def delta(self) -> int:
        return (self.new or 0) - (self.old or 0)

    def percent(self) -> str:
        if self.old is None:
            return "new"
        if self.new is None:
            return "removed"
        return "from 0" if self.old == 0 else "%+.2f %%" % (100 * self.delta / self.old)


@dataclass(frozen=True)
class SymbolDiff:
    """The largest section and symbol changes of one row, largest first, at most N of each."""
    sections: list[SizeChange] = field(default_factory=list)
    symbols: list[SizeChange] = field(default_factory=list)


def _largest(changes: list[SizeChange], count: int) -> list[SizeChange]:
    """The ``count`` changes of the largest size change (either way), ties by section and name."""
    moved = [c for c in changes if c.old != c.new]
    return sorted(moved, key=lambda c: (-abs(c.delta), c.section, c.name))[:count]


def compare_sections(before: dict[str, Section], after: dict[str, Section], count: int) -> SymbolDiff:
    """The ``count`` largest section changes and symbol changes between two images (a symbol is
    matched by name, whatever section holds it; it shows the section it is in now, or was)."""
    sections = [SizeChange(name, "", before[name].size if name in before else None,
                           after[name].size if name in after else None) for name in sorted(before.keys() | after.keys())]
    old = {symbol: (name, size) for name, s in before.items() for symbol, size in s.symbols.items()}
    new = {symbol: (name, size) for name, s in after.items() for symbol, size in s.symbols.items()}
    symbols = [SizeChange((new.get(symbol) or old[symbol])[0], symbol, old[symbol][1] if symbol in old else None,
                          new[symbol][1] if symbol in new else None) for symbol in sorted(old.keys() | new.keys())]
    return SymbolDiff(_largest(sections, count), _largest(symbols, count))
