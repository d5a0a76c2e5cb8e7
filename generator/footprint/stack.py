"""Worst-case stack of a linked image, from gcc's ``-fstack-usage`` files and the call graph of
its disassembly (docs/footprint.md, "Stack").

Each function's frame is the figure gcc wrote for it in a ``.su`` file (on AVR it includes the
return address the call pushed; on ARM ``bl`` pushes nothing). A function without one (libgcc's
and the C library's assembly routines, a library built without the flag) gets its frame from
its code when that is certain: its ``push`` instructions (and, on ARM, ``sub sp, #N``), and on
AVR the 2-byte return address, provided nothing else moves the stack pointer. The call graph
comes from ``objdump -d``: calls and jumps out of a function are edges (a tail call counted as a
call: an upper bound). A root's bound is the deepest path of frames from it.

A bound that cannot be known is not guessed: an indirect call (``icall``/``eicall``/``ijmp``,
``blx``/``bx`` to a register) whose targets the user did not declare (``--indirect
CALLER=TARGET,...``), a recursion, a dynamic frame (``alloca``, a variable-length array) or a
function whose frame is neither in a ``.su`` file nor certain from its code makes the root's
figure *unknown*, with the first reason found (``indirect call in kilo_start``).

Two figures per image: ``step``, the VM step (``svm_step``) with what it calls, and ``total``,
the whole program: ``main`` plus, on AVR, the deepest interrupt handler (avr-gcc's handlers
keep interrupts off, so they do not nest; one that turns them on again makes the total
unknown). The Cortex-M4 images measured here enable no interrupt, so the total is ``main``'s."""

import bisect
import re
import shutil
import subprocess
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from elftools.elf.constants import SH_FLAGS
from elftools.elf.elffile import ELFFile
from elftools.elf.sections import SymbolTableSection

from ..boundary.errors import ELF_MAX_BYTES, SU_MAX_BYTES, InputError, open_input, read_input
from ..targets import TARGETS

STEP_ROOT = "svm_step"
STEP_SOURCE = "swarmvm.c"                   # the VM core's source: svm_step and its static helpers
MAIN_ROOT = "main"
AVR_VECTOR = re.compile(r"^__vector_\d+$")
# libgcc's switch-table helpers: reached by a jump from a function's switch, their indirect jump
# lands on a case label of that same function, so they add no frame and call nothing.
SWITCH_TABLE_HELPERS = frozenset({"__tablejump__", "__tablejump2__"})
INSTRUCTION = re.compile(r"^\s*([0-9a-f]+):\s+(?:[0-9a-f]{2,8}\s)+\s*([a-z][\w.]*)\s*(.*)$")
AVR_TARGET = re.compile(r";\s*0x([0-9a-f]+)\b")
LABEL = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")              # the label line before an address's code
# Instructions after which code does not run on into the next address (a fragment of code that
# ends otherwise falls through into what follows, an edge of its own).
ENDS = {"avr": frozenset({"ret", "reti", "jmp", "rjmp", "ijmp", "eijmp"}), "arm": frozenset({"b", "bx"})}
ARM_TARGET = re.compile(r"^([0-9a-f]+) <")
AVR_SP = re.compile(r"^0x3[de]\b")
ARM_REGISTERS = re.compile(r"\{([^}]*)\}")
ARM_SP_IMMEDIATE = re.compile(r"^sp,\s*(sp,\s*)?#\d+")        # sp, #N and sp, sp, #N
ARM_POP_PC = re.compile(r"^pc,\s*\[sp\],\s*#4\b")


class StackUnknown(Exception):
    """A bound that cannot be known; the message says why (``indirect call in f``)."""


@dataclass
class Function:
    name: str
    start: int
    end: int
    file: str | None = None                     # the STT_FILE of a local symbol
    calls: set[int] = field(default_factory=set)          # target addresses
    indirect: bool = False
    pushes: int = 0                             # bytes the code's own pushes take
    moves_sp: bool = False                      # writes SP other than by push / sub sp, #N
    enables_interrupts: bool = False
    fragment: bool = False                      # code in no sized function (see _fragments)
    last: tuple[str, str] = ("", "")            # its last instruction: mnemonic, operands


@dataclass(frozen=True)
class Stack:
    """Worst-case bytes of the VM step and of the whole program; None with the reason when not
    known."""
    step: int | None
    total: int | None
    unknown: dict[str, str]                     # "step" / "total" -> why it is not known

    def as_json(self) -> dict[str, object]:
        known: dict[str, object] = {key: value for key, value in (("step", self.step), ("total", self.total)) if value is not None}
        return dict(known, unknown=self.unknown) if self.unknown else known


def parse_indirect(declarations: Sequence[str], file: str = "") -> dict[str, tuple[str, ...]]:
    """``CALLER=TARGET,TARGET`` declarations (``--indirect``, or those of the sidecar ``file``) as
    {caller: targets}; InputError naming the one that is not of that form."""
    found: dict[str, tuple[str, ...]] = {}
    for index, text in enumerate(declarations):
        caller, equals, targets = (part.strip() for part in text.partition("="))
        names = tuple(t.strip() for t in targets.split(",") if t.strip())
        if not equals or not caller or not names:
            raise InputError(file, "indirect[%d]" % index, "%r is not CALLER=TARGET[,TARGET...]" % text)
        found[caller] = found.get(caller, ()) + names
    return found


def parse_frames(declarations: Sequence[str]) -> dict[str, int]:
    """``FUNCTION=BYTES`` declarations (``--frame``) as {function: bytes}: the frame of a function
    that has no .su entry and whose code alone does not make it certain (a library built without
    -fstack-usage), the return address included, as gcc counts it on AVR; InputError naming the
    one that is not of that form."""
    found: dict[str, int] = {}
    for index, text in enumerate(declarations):
        name, equals, size = (part.strip() for part in text.partition("="))
        if not equals or not name or not size.isdigit():
            raise InputError("", "frame[%d]" % index, "%r is not FUNCTION=BYTES" % text)
        found[name] = int(size)
    return found


def su_files(elf: Path, folders: tuple[Path, ...] = ()) -> list[Path]:
    """The ``.su`` files of an image: ``<elf name>-*.su`` beside it (gcc 11 and later, compiling
    and linking in one command), else every ``*.su`` in its folder (a build that compiled there,
    as the generated Kilobot Makefile does); and every ``*.su`` in ``folders``."""
    own = sorted(elf.parent.glob(elf.name + "-*.su"))
    found = own or sorted(elf.parent.glob("*.su"))
    for folder in folders:
        found += sorted(Path(folder).glob("*.su"))
    return found


def read_su(paths: list[Path]) -> dict[tuple[str, str], int | None]:
    """{(source file name, function): bytes, or None for a dynamic, unbounded frame}."""
    frames: dict[tuple[str, str], int | None] = {}
    for path in paths:
        for line in read_input(str(path), limit=SU_MAX_BYTES).decode("utf-8", "replace").splitlines():
            fields = line.split("\t")
            if len(fields) != 3:
                continue
            where, size, kind = fields
            source, _, name = where.rpartition(":")
            source = Path(source.split(":")[0]).name
            bounded = "dynamic" not in kind or "bounded" in kind
            previous = frames.get((source, name), 0)
            frames[(source, name)] = max(previous, int(size)) if bounded and previous is not None else None
    return frames


def _functions(elf_path: Path) -> dict[int, Function]:
    """Functions of the image by start address (Thumb bit cleared), aliases once: sized
    symbols (libgcc's assembly routines are sized symbols without a type), and global code
    symbols without a size (an assembly routine such as kilolib's ``message_send``), which run
    to the next function or the end of their section."""
    functions: dict[int, Function] = {}
    unsized: dict[int, tuple[str, int]] = {}
    with open_input(str(elf_path), ELF_MAX_BYTES) as handle:
        elf = ELFFile(handle)
        table = elf.get_section_by_name(".symtab")
        code = {i: s["sh_addr"] + s["sh_size"] for i, s in enumerate(elf.iter_sections())
                if s["sh_flags"] & SH_FLAGS.SHF_EXECINSTR}
        current_file = None
        for symbol in table.iter_symbols() if isinstance(table, SymbolTableSection) else ():
            kind, bind = symbol["st_info"]["type"], symbol["st_info"]["bind"]
            if kind == "STT_FILE":
                current_file = symbol.name
            elif kind not in ("STT_FUNC", "STT_NOTYPE") or symbol["st_shndx"] not in code:
                continue
            start = symbol["st_value"] & ~1
            if symbol["st_size"]:
                functions.setdefault(start, Function(symbol.name, start, start + symbol["st_size"],
                                                     current_file if bind == "STB_LOCAL" else None))
            elif bind != "STB_LOCAL" and not symbol.name.startswith("$"):
                unsized.setdefault(start, (symbol.name, code[symbol["st_shndx"]]))
    starts = sorted(set(functions) | set(unsized))
    for start, (name, section_end) in unsized.items():
        if start in functions or _containing(functions, sorted(functions), start) is not None:
            continue
        later = [s for s in starts if s > start]
        functions[start] = Function(name, start, min(later[0], section_end) if later else section_end)
    return functions


def _containing(functions: dict[int, Function], starts: list[int], address: int) -> Function | None:
    index = bisect.bisect_right(starts, address) - 1
    if index >= 0 and functions[starts[index]].start <= address < functions[starts[index]].end:
        return functions[starts[index]]
    return None


def _read_avr(function: Function, address: int, mnemonic: str, operands: str, next_address: int) -> None:
    if mnemonic in ("icall", "eicall", "ijmp", "eijmp"):
        function.indirect = True
    elif mnemonic == "push":
        function.pushes += 1
    elif mnemonic == "sei":
        function.enables_interrupts = True
    elif mnemonic == "out" and AVR_SP.match(operands):
        function.moves_sp = True
    elif mnemonic.startswith("br") and AVR_TARGET.search(operands):
        target = int(AVR_TARGET.search(operands).group(1), 16)    # type: ignore[union-attr]
        if not function.start <= target < function.end:
            function.calls.add(target)          # a branch out of the function (assembly routines)
    elif mnemonic in ("call", "rcall", "jmp", "rjmp"):
        match = AVR_TARGET.search(operands)
        target = int(match.group(1), 16) if match else int(operands.split()[0], 16)
        if mnemonic == "rcall" and target == next_address:
            function.pushes += 2                # `rcall .+0`: two bytes of frame
        elif mnemonic in ("jmp", "rjmp") and target == 0:
            pass                                # to the reset vector (avr-libc's __bad_interrupt): a restart
        elif not function.start <= target < function.end:
            function.calls.add(target)


def _read_arm(function: Function, address: int, mnemonic: str, operands: str, next_address: int) -> None:
    base = mnemonic.split(".")[0]
    registers = ARM_REGISTERS.search(operands)
    if base in ("push", "stmdb") and (base == "push" or operands.startswith("sp!")) and registers:
        function.pushes += 4 * len(_register_list(registers.group(1)))
    elif base == "vpush" and registers:
        names = _register_list(registers.group(1))
        function.pushes += sum(8 if name.startswith("d") else 4 for name in names)
    elif base in ("sub", "subw") and ARM_SP_IMMEDIATE.match(operands):
        function.pushes += int(operands.rpartition("#")[2].split()[0])
    elif base in ("blx", "bx") and not ARM_TARGET.match(operands):
        if operands.split()[0] != "lr":
            function.indirect = True
    elif base == "ldr" and ARM_POP_PC.match(operands):
        pass                                    # `ldr pc, [sp], #4`: a return (pop {pc})
    elif (re.match(r"^(mov|add|ldr|pop|ldm)", base) and re.match(r"^pc\b", operands)):
        function.indirect = True
    elif base in ("add", "addw") and ARM_SP_IMMEDIATE.match(operands):
        pass                                    # `add sp, #N`: the frame given back
    elif re.match(r"^(mov|add|sub|ldr)", base) and re.match(r"^sp,", operands):
        function.moves_sp = True
    elif re.match(r"^(bl|blx|b|b[a-z]{2}|cbn?z)$", base):
        match = ARM_TARGET.match(operands) or ARM_TARGET.match(operands.split(",")[-1].strip())
        if match:
            target = int(match.group(1), 16)
            if not function.start <= target < function.end:
                function.calls.add(target)


def _register_list(text: str) -> list[str]:
    """``r4-r7, lr`` -> r4 r5 r6 r7 lr; ``d8-d15`` likewise."""
    names = []
    for part in (p.strip() for p in text.split(",") if p.strip()):
        first, dash, last = part.partition("-")
        if dash and first[1:].isdigit() and last[1:].isdigit():
            names += ["%s%d" % (first[0], n) for n in range(int(first[1:]), int(last[1:]) + 1)]
        else:
            names.append(part)
    return names


@dataclass(frozen=True)
class Architecture:
    """How the call graph of one instruction set is read: its disassembler, the reader of its
    instructions, what a call pushes (a function without a .su entry gets it in its frame),
    where a comment starts in an operand, and whether interrupt handlers add to the total."""
    objdump: str
    reader: Callable[[Function, int, str, str, int], None]
    call_pushes: int
    comment: str | None
    handlers: re.Pattern[str] | None        # the handlers' names: the deepest one adds to main's


# The instruction sets whose call graphs are read, by the name a target's record gives them
# (targets.record.Elf): on AVR a call pushes its 2-byte return address, on ARM ``bl`` pushes nothing.
ARCHITECTURES = {
    "avr": Architecture("avr-objdump", _read_avr, call_pushes=2, comment=None, handlers=AVR_VECTOR),
    "arm": Architecture("arm-none-eabi-objdump", _read_arm, call_pushes=0, comment="@", handlers=None),
}


def architecture(target: str) -> Architecture:
    """The architecture of ``target``'s images (its record's ``elf``); StackUnknown when it has none."""
    elf = TARGETS[target].elf
    if elf is None or elf.architecture not in ARCHITECTURES:
        raise StackUnknown("no call-graph reader for target %s's images" % target)
    return ARCHITECTURES[elf.architecture]


def read_code(elf_path: Path, target: str) -> dict[int, Function]:
    """The image's functions with their calls and pushes, from ``objdump -d``."""
    arch = architecture(target)
    tool = shutil.which(arch.objdump)
    if tool is None:
        raise StackUnknown("%s not found (needed to read the call graph)" % arch.objdump)
    functions = _functions(elf_path)
    listing = subprocess.run([tool, "-d", str(elf_path)],
                             capture_output=True, text=True, check=True).stdout
    instructions, labels = [], []
    for line in listing.splitlines():
        label = LABEL.match(line)
        if label:
            labels.append((int(label.group(1), 16), label.group(2)))
        match = INSTRUCTION.match(line)
        if match:
            instructions.append((int(match.group(1), 16), match.group(2), match.group(3).strip()))
    _fragments(functions, instructions, labels)
    starts = sorted(functions)
    for index, (address, mnemonic, operands) in enumerate(instructions):
        function = _containing(functions, starts, address)
        if function is not None:
            following = instructions[index + 1][0] if index + 1 < len(instructions) else address + 2
            operands = operands.split(arch.comment)[0].strip() if arch.comment else operands
            arch.reader(function, address, mnemonic, operands, following)
            function.last = (mnemonic, operands)
    name = TARGETS[target].elf.architecture                 # type: ignore[union-attr]  # architecture() checked it
    for function in functions.values():
        if function.fragment and not _ends(name or "", *function.last):
            function.calls.add(function.end)    # runs on into the next code: counted as a call
    return functions


def _fragments(functions: dict[int, Function], instructions: list[tuple[int, str, str]],
               labels: list[tuple[int, str]]) -> None:
    """Functions for the code that lies in no sized function: avr-libc's float routines give
    ``__addsf3`` no size, so the code between ``__subsf3``'s end and ``__addsf3x`` is in none,
    and ``__addsf3x`` jumps into it. Each run of such instructions becomes a function of its own,
    named as objdump labels its first address (``__addsf3+0xc``), read like any other; one that
    does not end in a return or jump runs on into what follows, an edge (read_code). Its frame
    is then what its code shows, plus what a call pushes, an upper bound for code entered by a
    jump."""
    starts = sorted(functions)
    label_starts = [address for address, _ in labels]
    current: Function | None = None
    for index, (address, _, _) in enumerate(instructions):
        following = instructions[index + 1][0] if index + 1 < len(instructions) else address + 2
        if _containing(functions, starts, address) is not None:
            current = None
            continue
        if current is not None and current.end == address and address not in functions:
            current.end = following
            continue
        at = bisect.bisect_right(label_starts, address) - 1
        name = "0x%x" % address if at < 0 else labels[at][1] if labels[at][0] == address else \
            "%s+0x%x" % (labels[at][1], address - labels[at][0])
        current = Function(name, address, following, fragment=True)
        functions[address] = current
    for function in functions.values():     # a fragment stops where the next function starts
        if function.fragment:
            later = [s for s in starts if s > function.start]
            if later and later[0] < function.end:
                function.end = later[0]


def _ends(architecture_name: str, mnemonic: str, operands: str) -> bool:
    """Whether code does not run on past this instruction (a return, an unconditional jump)."""
    base = mnemonic.split(".")[0]
    if base in ENDS.get(architecture_name, frozenset()):
        return True
    return architecture_name == "arm" and (base in ("pop", "ldm", "ldmia") and "pc" in operands
                                           or base == "ldr" and operands.startswith("pc"))


@dataclass
class CallGraph:
    """Frames and calls of an image's functions, and the bound of a root."""
    target: str
    functions: dict[int, Function]
    frames: dict[tuple[str, str], int | None]
    indirect: dict[str, tuple[str, ...]]
    bounds: dict[int, int] = field(default_factory=dict)
    declared_frames: dict[str, int] = field(default_factory=dict)       # --frame, for functions without .su

    def named(self, name: str) -> list[Function]:
        return [f for f in self.functions.values() if f.name == name]

    def frame(self, function: Function) -> int:
        """Bytes of a function's own frame: its .su figure, else what its code shows."""
        if function.name in SWITCH_TABLE_HELPERS:
            return 0
        candidates = [size for (source, name), size in self.frames.items()
                      if name == function.name or name == re.sub(r"\.\d+$", "", function.name)]
        if function.file is not None:
            own = [size for (source, name), size in self.frames.items() if source == Path(function.file).name
                   and (name == function.name or name == re.sub(r"\.\d+$", "", function.name))]
            candidates = own or candidates
        if candidates:
            if any(size is None for size in candidates):
                raise StackUnknown("dynamic stack frame in %s" % function.name)
            return max(c for c in candidates if c is not None)
        if function.name in self.declared_frames:
            return self.declared_frames[function.name]
        if function.moves_sp:
            raise StackUnknown("no stack usage data for %s (no .su entry, and its code moves the stack pointer): "
                               "compile it with -fstack-usage and put its .su file beside the ELF, or declare its "
                               "frame with --frame %s=BYTES" % (function.name, function.name))
        return function.pushes + architecture(self.target).call_pushes

    def declared(self, function: Function) -> tuple[str, ...] | None:
        """What an indirect call in ``function`` may reach: its own declaration, or, for a
        static function of the VM core's step (``fire``, ``step_m``: svm_step's code that the
        compiler kept out of line, as arm-none-eabi-gcc -Os does), ``svm_step``'s."""
        if function.name in self.indirect:
            return self.indirect[function.name]
        if function.file is not None and Path(function.file).name == STEP_SOURCE:
            return self.indirect.get(STEP_ROOT)
        return None

    def callees(self, function: Function) -> list[Function]:
        found = []
        if function.indirect and function.name not in SWITCH_TABLE_HELPERS:
            declared = self.declared(function)
            if declared is None:
                raise StackUnknown("indirect call in %s" % function.name)
            for name in declared:
                found += self.named(name)
            if not found:
                raise StackUnknown("indirect call in %s: none of its declared targets (%s) is in the image"
                                   % (function.name, ", ".join(declared)))
        starts = sorted(self.functions)
        for address in sorted(function.calls):
            callee = _containing(self.functions, starts, address)
            if callee is None:
                raise StackUnknown("%s calls 0x%x, in no sized function" % (function.name, address))
            found.append(callee)
        return found

    def bound(self, function: Function, path: tuple[int, ...] = ()) -> int:
        """Worst-case bytes from entering ``function``: its frame and its deepest callee's."""
        if function.start in path:
            raise StackUnknown("recursion through %s" % function.name)
        if function.start not in self.bounds:
            deepest = max((self.bound(c, path + (function.start,)) for c in self.callees(function)), default=0)
            self.bounds[function.start] = self.frame(function) + deepest
        return self.bounds[function.start]

    def root(self, name: str) -> int:
        found = self.named(name)
        if not found:
            raise StackUnknown("no function %s in the image" % name)
        return max(self.bound(f) for f in found)

    def program(self) -> int:
        """``main`` plus the deepest interrupt handler (AVR; handlers that do not nest)."""
        total = self.root(MAIN_ROOT)
        names = architecture(self.target).handlers
        if names is None:
            return total
        handlers = [f for f in self.functions.values() if names.match(f.name)]
        for handler in handlers:
            if handler.enables_interrupts:
                raise StackUnknown("interrupts enabled again in handler %s (they may nest)" % handler.name)
        return total + max((self.bound(h) for h in handlers), default=0)


def measure_stack(elf: str, target: str, indirect: dict[str, tuple[str, ...]] | None = None,
                  su_folders: tuple[Path, ...] = (), frames: dict[str, int] | None = None) -> Stack:
    """The worst-case stack of the VM step and of the whole program of a linked image; ``frames``:
    the declared frames of functions without a .su entry (parse_frames)."""
    paths = su_files(Path(elf), su_folders)
    if not paths:
        reason = "no -fstack-usage data (.su files) beside %s" % Path(elf).name
        return Stack(None, None, {"step": reason, "total": reason})
    try:
        graph = CallGraph(target, read_code(Path(elf), target), read_su(paths), dict(indirect or {}),
                          declared_frames=dict(frames or {}))
    except subprocess.CalledProcessError as exc:
        reason = "%s could not read it (%s)" % (architecture(target).objdump, exc.stderr.strip().splitlines()[-1:])
        return Stack(None, None, {"step": reason, "total": reason})
    except StackUnknown as exc:
        return Stack(None, None, {"step": str(exc), "total": str(exc)})
    values: dict[str, int | None] = {}
    unknown: dict[str, str] = {}
    figures: tuple[tuple[str, Callable[[], int]], ...] = (("step", lambda: graph.root(STEP_ROOT)), ("total", graph.program))
    for key, figure in figures:
        try:
            values[key] = figure()
        except StackUnknown as exc:
            values[key], unknown[key] = None, str(exc)
    return Stack(values["step"], values["total"], unknown)
