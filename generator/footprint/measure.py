"""Memory footprint of linked VM images: flash and static RAM, split into VM core, tables and
application, with the robots' hard limits and the seed's 100 kB KPI (docs/footprint.md).

The target of an image is the one whose record (swarmvm.targets, its ``elf``) recognises it:
its machine, and the symbols that tell two targets of one machine apart (:func:`recognise`).

Only linked ELF files are read (pyelftools), so the figures are what the device holds:

- a section is *flash* when it is loaded and read-only (code, constants, the image in
  PROGMEM), *RAM* when it is writable and takes no file space (``.bss``, ``.noinit``), and
  *both* when it is writable with contents (``.data``: its initialiser sits in flash and is
  copied to RAM at reset). AVR's ``.eeprom``, fuse, lock and signature sections are neither.
- the **tables** are the table image: the object whose bytes start with the image magic and
  whose size is the image's own length field, wherever the build put it.
- the **VM core** is what ``runtime_c/*.c`` defines (but for the robot runtimes a target's
  record names, such as ``swarmvm_kilobot.c``, which are application): a global symbol whose name one of those
  files defines at file scope, a local symbol listed after the ``STT_FILE`` entry of one of
  those files, and the VM instance (an object named ``vm`` or ``..._vm``) wherever it lives.
- the **application** is the rest of each total: start-up code, C library, generated glue,
  callbacks, and bytes no symbol accounts for (vector tables, alignment).
"""

import dataclasses
import hashlib
import os
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from importlib.abc import Traversable
from typing import TYPE_CHECKING, Any, Iterator, Union

from elftools.elf.constants import SH_FLAGS
from elftools.elf.elffile import ELFFile
from elftools.elf.sections import Section, Symbol, SymbolTableSection

from ..boundary.errors import ELF_MAX_BYTES, open_input
from .stack import Stack

if TYPE_CHECKING:
    from .cycles import Cycles
from ..compiler.runtime_files import (
    CPP_COMPAT_HEADERS,
    CPP_VM_HEADERS,
    RUNTIME_C,
    RUNTIME_CPP,
    RUNTIME_PY_DIR,
    image_format,
)
from ..targets import TARGETS
from ..targets.record import RobotLimits

FORMAT = image_format()
ElfPath = Union[str, "os.PathLike[str]"]
NOT_MEMORY = (".eeprom", ".fuse", ".lock", ".signature", ".user_signatures")
VM_INSTANCE = re.compile(r"(^|_)vm$")
# An external definition in the runtime's C sources: a line starting in column 0 with a type
# (not static) and ending the declarator at '(' (function), '[' / '=' / ';' (object).
DEFINITION = re.compile(r"^(?!typedef|extern|static|#)[A-Za-z_][\w\s\*]*?\**\b([A-Za-z_]\w*)\s*[\(\[=;]", re.M)

VM_KPI = 100000                        # the seed's KPI: a VM below 100 kB
SEED_KPI_SOURCE = {"C++ VM (published)": 15699, "Python VM (published)": 7343}


def robot_limits() -> dict[str, RobotLimits]:
    """The hard limits of every target whose record has them, by target."""
    return {name: target.limits for name, target in sorted(TARGETS.items()) if target.limits is not None}


@dataclass(frozen=True)
class Limits:
    """What every row is checked against: its robot's hard limits (by target, the records' by
    default) and the seed's KPI on the VM."""
    robots: Mapping[str, RobotLimits] = field(default_factory=robot_limits)
    vm: int = VM_KPI

    def replaced(self, target: str, flash: int | None = None, sram: int | None = None,
                 min_stack: int | None = None) -> "Limits":
        """These limits with the figures given of ``target``'s robot replaced."""
        old = self.robots[target]
        robot = RobotLimits(old.robot, old.flash if flash is None else flash, old.sram if sram is None else sram,
                            old.min_stack if min_stack is None else min_stack)
        return dataclasses.replace(self, robots={**self.robots, target: robot})

    def as_json(self) -> dict[str, int]:
        """``<target>_flash``, ``<target>_sram``, ``<target>_min_stack`` of each robot, then ``vm``."""
        figures = {"%s_%s" % (target, key): getattr(robot, key)
                   for target, robot in self.robots.items() for key in ("flash", "sram", "min_stack")}
        return dict(figures, vm=self.vm)


@dataclass
class Split:
    total: int = 0
    core: int = 0
    tables: int = 0
    application: int = 0


@dataclass
class Footprint:
    target: str
    supervisor: str
    elf: str
    flash: Split = field(default_factory=Split)
    ram: Split = field(default_factory=Split)
    stack: Stack | None = None          # worst-case stack (footprint_stack), when measured
    cycles: "Cycles | None" = None      # cycles per step with an event script (footprint_cycles)
    tables_sha256: str | None = None    # the table image's digest: matches a renamed ELF with its baseline row
    indirect: dict[str, tuple[str, ...]] = field(default_factory=dict)   # the declarations its stack used
    elf_sha256: str | None = None       # what the figures are of: the file's digest and the toolchain it names
    frames: dict[str, int] = field(default_factory=dict)     # frames declared with --frame
    compiler: tuple[str, ...] = ()

    @property
    def vm(self) -> int:
        """The VM proper (core and tables, flash and RAM), the figure the seed's KPI bounds."""
        return self.flash.core + self.flash.tables + self.ram.core + self.ram.tables

    def as_json(self) -> dict[str, Any]:
        """The image as the JSON report writes it (and a baseline holds it)."""
        image: dict[str, Any] = dict(target=self.target, supervisor=self.supervisor, elf=self.elf, flash=asdict(self.flash),
                     ram=asdict(self.ram), vm=self.vm)
        if self.tables_sha256 is not None:
            image["tables_sha256"] = self.tables_sha256
        if self.elf_sha256 is not None:
            image.update(elf_sha256=self.elf_sha256, compiler=list(self.compiler))
        if self.indirect:
            image["indirect"] = {caller: list(targets) for caller, targets in sorted(self.indirect.items())}
        if self.frames:
            image["frames"] = dict(sorted(self.frames.items()))
        if self.stack is not None:
            image["stack"] = self.stack.as_json()
        if self.cycles is not None:
            image["cycles"] = self.cycles.as_json()
        return image


@dataclass(frozen=True)
class Column:
    """One figure of a row: its budget key, its heading in the tables, where the JSON report
    holds it, and its unit. Budgets, deltas, the tables and the checks all go by this list, so a
    figure added here (a worst-case stack, cycles per step) is budgeted and compared like the rest;
    a row that lacks a column's figure (not measured) is left out of that column's checks."""
    key: str
    label: str
    path: tuple[str, ...]
    unit: str = "B"


COLUMNS = (Column("flash", "flash", ("flash", "total")), Column("flash_core", "VM core", ("flash", "core")),
           Column("flash_tables", "tables", ("flash", "tables")),
           Column("flash_application", "application", ("flash", "application")),
           Column("ram", "RAM", ("ram", "total")), Column("ram_core", "VM core", ("ram", "core")),
           Column("ram_tables", "tables", ("ram", "tables")),
           Column("ram_application", "application", ("ram", "application")),
           Column("vm", "VM", ("vm",)), Column("stack", "stack", ("stack", "total")),
           Column("stack_step", "VM step stack", ("stack", "step")),
           Column("cycles_mean", "cycles/step", ("cycles", "mean"), "cycles"),
           Column("cycles", "worst cycles/step", ("cycles", "worst"), "cycles"))
COLUMN = {column.key: column for column in COLUMNS}
STACK_COLUMN = {"total": "stack", "step": "stack_step"}    # Stack's figures -> their columns


@dataclass(frozen=True)
class Row:
    """A row of a report, measured now or read from a baseline: the figures by column key, and
    why a figure that was measured is not known (a stack bound: ``indirect call in f``); what
    tells a comparison whether the rows are comparable: the table image's digest (a renamed ELF
    of the same supervisor), the event script's digest (cycles of one script only), and the
    budgets the row was checked against (a changed budget is shown)."""
    target: str
    supervisor: str
    values: dict[str, int]
    unknown: dict[str, str] = field(default_factory=dict)
    tables_sha256: str | None = None
    script_sha256: str | None = None
    budget: dict[str, int] = field(default_factory=dict)

    @property
    def name(self) -> str:
        return "%s/%s" % (self.target, self.supervisor)


def column_value(image: dict[str, Any], column: Column) -> Any:
    """The figure of ``column`` in a JSON image, or None when the image does not hold it."""
    value: Any = image
    for key in column.path:
        if not isinstance(value, dict) or key not in value:
            return None
        value = value[key]
    return value


def row_of(footprint: Footprint) -> Row:
    image = footprint.as_json()
    values = {c.key: column_value(image, c) for c in COLUMNS}
    unknown = {STACK_COLUMN[key]: reason for key, reason in image.get("stack", {}).get("unknown", {}).items()}
    script = footprint.cycles.digest if footprint.cycles is not None else None
    return Row(footprint.target, footprint.supervisor, {k: v for k, v in values.items() if v is not None}, unknown,
               footprint.tables_sha256, script or None)


class FootprintError(Exception):
    """An ELF that cannot be measured (no table image in it, unknown machine, a section or
    symbol that lies outside what it belongs to)."""


# Robot runtimes in runtime_c/ that run the VM as a program (kilolib's setup/loop, messages):
# what a robot application needs around the VM, so they count as application, not VM core.
PLATFORM_RUNTIMES = frozenset(name for target in TARGETS.values() if target.elf is not None
                              for name in target.elf.platform_runtime)


def runtime_names(runtime: Traversable = RUNTIME_C) -> tuple[set[str], set[str]]:
    """(global names the runtime's C sources define, their file names), platform runtimes aside."""
    names: set[str] = set()
    files: set[str] = set()
    for source in sorted(Path(str(runtime)).glob("*.c")):
        if source.name in PLATFORM_RUNTIMES:
            continue
        files.add(source.name)
        names.update(DEFINITION.findall(source.read_text()))
    return names, files


def _memory_kind(section: Section) -> str | None:
    """'flash', 'ram', 'both' or None for a section of a linked image."""
    flags = section["sh_flags"]
    if not flags & SH_FLAGS.SHF_ALLOC or section.name in NOT_MEMORY or section["sh_size"] == 0:
        return None
    if not flags & SH_FLAGS.SHF_WRITE:
        return "flash"
    return "ram" if section["sh_type"] == "SHT_NOBITS" else "both"


def _check_section(path: ElfPath, section: Section, file_size: int) -> None:
    """FootprintError unless a memory section with contents lies within the file: its size is
    counted and its bytes read (an image's header), so one that runs past the end would give
    figures, or a read, that the file does not hold."""
    if section["sh_type"] != "SHT_NOBITS" and section["sh_offset"] + section["sh_size"] > file_size:
        raise FootprintError("%s: section %s (%d B at offset %d) runs past the end of the file (%d B)"
                             % (path, section.name, section["sh_size"], section["sh_offset"], file_size))


def _check_symbol(path: ElfPath, elf: ELFFile, symbol: Symbol) -> None:
    """FootprintError unless a sized symbol lies inside the section it names: its size is
    counted in that section's bucket, and an image's bytes are read from there."""
    index = symbol["st_shndx"]
    if index >= elf.num_sections():
        raise FootprintError("%s: symbol %s names section %d of %d" % (path, symbol.name, index, elf.num_sections()))
    section = elf.get_section(index)
    thumb = symbol["st_info"]["type"] == "STT_FUNC"      # an ARM Thumb function's address has bit 0 set
    start = (symbol["st_value"] & ~1 if thumb else symbol["st_value"]) - section["sh_addr"]
    if start < 0 or start + symbol["st_size"] > section["sh_size"]:
        raise FootprintError("%s: symbol %s (%d B at 0x%x) lies outside its section %s (%d B at 0x%x)"
                             % (path, symbol.name, symbol["st_size"], symbol["st_value"], section.name,
                                section["sh_size"], section["sh_addr"]))


def _symbols(elf: ELFFile) -> Iterator[tuple[Symbol, str | None]]:
    """(symbol, defining file or None) for every sized object and function, an alias (a second
    symbol at the same address of the same section) once. Only an ARM function's address has its
    Thumb bit cleared: on AVR an object may sit at an odd address, and clearing bit 0 there would
    take it for an alias of the one before it."""
    table = elf.get_section_by_name(".symtab")
    if not isinstance(table, SymbolTableSection):
        raise FootprintError("no symbol table (stripped image)")
    thumb = elf["e_machine"] == "EM_ARM"
    seen: set[tuple[int, int]] = set()
    current_file: str | None = None
    for symbol in table.iter_symbols():
        kind, bind = symbol["st_info"]["type"], symbol["st_info"]["bind"]
        if kind == "STT_FILE":
            current_file = symbol.name
            continue
        if kind not in ("STT_FUNC", "STT_OBJECT") or symbol["st_size"] == 0:
            continue
        if not isinstance(symbol["st_shndx"], int):
            continue
        key = (symbol["st_shndx"], symbol["st_value"] & ~1 if thumb and kind == "STT_FUNC" else symbol["st_value"])
        if key in seen:
            continue
        seen.add(key)
        yield symbol, (current_file if bind == "STB_LOCAL" else None)


def _is_image(elf: ELFFile, symbol: Symbol) -> bool:
    """Whether an object symbol holds a table image (magic, and its length field = its size)."""
    if symbol["st_info"]["type"] != "STT_OBJECT" or symbol["st_size"] < FORMAT.MIN_IMAGE_SIZE:
        return False
    section = elf.get_section(symbol["st_shndx"])
    if section["sh_type"] == "SHT_NOBITS":
        return False
    start = symbol["st_value"] - section["sh_addr"]         # inside the section: _check_symbol
    header = FORMAT.Header.unpack(section.data()[start:start + FORMAT.HEADER_SIZE])
    return bool(header.magic == FORMAT.MAGIC and header.length == symbol["st_size"])


def table_image(path: ElfPath) -> bytes:
    """The bytes of the table image linked into an ELF (the first symbol holding one)."""
    with open_input(os.fspath(path), ELF_MAX_BYTES) as handle:
        elf = ELFFile(handle)
        for symbol, _ in _symbols(elf):
            _check_symbol(path, elf, symbol)
            if _is_image(elf, symbol):
                section = elf.get_section(symbol["st_shndx"])
                start = symbol["st_value"] - section["sh_addr"]
                data: bytes = section.data()[start:start + symbol["st_size"]]
                return data
    raise FootprintError("%s: no table image (magic %r) found among its symbols" % (path, FORMAT.MAGIC.decode()))


def recognise(path: ElfPath, machine: str, symbols: Callable[[], Iterable[str]]) -> str:
    """The target whose record recognises an ELF of ``machine`` defining ``symbols()`` (read only
    when a record asks for symbols): of the targets of that machine whose symbols it all defines,
    the one asking for the most (targets.record.Elf); FootprintError when none is, or two are equally."""
    candidates = [(name, t.elf.symbols) for name, t in sorted(TARGETS.items())
                  if t.elf is not None and t.elf.machine == machine]
    names = set(symbols()) if any(wanted for _, wanted in candidates) else set()
    found = sorted(((len(wanted), name) for name, wanted in candidates if names.issuperset(wanted)), reverse=True)
    if not found:
        raise FootprintError("%s: machine %s is not a known VM target" % (path, machine))
    if len(found) > 1 and found[0][0] == found[1][0]:
        raise FootprintError("%s: both targets %s and %s recognise this %s image: one of their records must ask "
                             "for a symbol the other's images lack" % (path, found[1][1], found[0][1], machine))
    return found[0][1]


def measure(path: ElfPath, supervisor: str | None = None, target: str | None = None,
            runtime: Traversable = RUNTIME_C) -> Footprint:
    """The Footprint of one linked ELF; target from its machine, supervisor from its name."""
    core_names, core_files = runtime_names(runtime)
    with open_input(os.fspath(path), ELF_MAX_BYTES) as handle:
        file_size = os.fstat(handle.fileno()).st_size
        elf = ELFFile(handle)
        if target is None:
            target = recognise(path, elf["e_machine"], lambda: (symbol.name for symbol, _ in _symbols(elf)))
        result = Footprint(target, supervisor or Path(path).stem, str(path))
        kinds: dict[int, str | None] = {}
        for index, section in enumerate(elf.iter_sections()):
            kind = _memory_kind(section)
            kinds[index] = kind
            if kind is not None:
                _check_section(path, section, file_size)
            if kind in ("flash", "both"):
                result.flash.total += section["sh_size"]
            if kind in ("ram", "both"):
                result.ram.total += section["sh_size"]
        images = 0
        for symbol, local_file in _symbols(elf):
            _check_symbol(path, elf, symbol)
            kind = kinds[symbol["st_shndx"]]
            if kind is None:
                continue
            if _is_image(elf, symbol):
                bucket = "tables"
                images += 1
                if result.tables_sha256 is None:
                    section = elf.get_section(symbol["st_shndx"])
                    start = symbol["st_value"] - section["sh_addr"]
                    result.tables_sha256 = hashlib.sha256(section.data()[start:start + symbol["st_size"]]).hexdigest()
            elif (local_file in core_files if local_file is not None else symbol.name in core_names) \
                    or (symbol["st_info"]["type"] == "STT_OBJECT" and VM_INSTANCE.search(symbol.name)):
                bucket = "core"
            else:
                continue
            for split, counted in ((result.flash, ("flash", "both")), (result.ram, ("ram", "both"))):
                if kind in counted:
                    setattr(split, bucket, getattr(split, bucket) + symbol["st_size"])
        if images == 0:
            raise FootprintError("%s: no table image (magic %r) found among its symbols" % (path, FORMAT.MAGIC.decode()))
        comment = elf.get_section_by_name(".comment")          # the compilers that built it ("GCC: (GNU) 5.4.0")
        if comment is not None and comment["sh_type"] != "SHT_NOBITS":
            result.compiler = tuple(dict.fromkeys(text.decode("utf-8", "replace").strip() for text in
                                                  comment.data().split(b"\0") if text.strip()))
        handle.seek(0)
        digest = hashlib.sha256()
        for block in iter(lambda: handle.read(1 << 16), b""):
            digest.update(block)
        result.elf_sha256 = digest.hexdigest()
    for split in (result.flash, result.ram):
        split.application = split.total - split.core - split.tables
    return result


# The seed's KPI measure, bytes of source, per runtime (docs/footprint.md, "Source size"): each
# row's folder and files. A VM's row counts what a robot runs of it; the C++ compatibility layer
# (published SCT programs, swarmvm_compat.hpp) has a row of its own.
SOURCE_ROWS = (
    ("Python VM (runtime_py/swarmvm_vm.py + swarmvm_format.py + swarmvm_step_source.py)", RUNTIME_PY_DIR,
     ("swarmvm_vm.py", "swarmvm_format.py", "swarmvm_step_source.py")),
    ("C VM core (runtime_c/swarmvm.c + swarmvm.h + swarmvm_format.h)", RUNTIME_C,
     ("swarmvm.c", "swarmvm.h", "swarmvm_format.h")),
    ("C++ VM (runtime_cpp/%s)" % " + ".join(CPP_VM_HEADERS), RUNTIME_CPP, CPP_VM_HEADERS),
    ("C++ compatibility layer (runtime_cpp/%s)" % " + ".join(CPP_COMPAT_HEADERS), RUNTIME_CPP, CPP_COMPAT_HEADERS),
)


def source_sizes() -> dict[str, int]:
    """Bytes of source of each runtime (SOURCE_ROWS), to compare with the seed's KPI table."""
    return {name: sum(len((folder / n).read_bytes()) for n in files) for name, folder, files in SOURCE_ROWS}
