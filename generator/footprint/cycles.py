"""Cycles per VM step of a linked image, run in an emulator with an event script
(docs/footprint.md, "Cycles per step").

A Kilobot image runs unchanged on simavr's ATmega328P through the project's Kilobot board
(swarmvm.footprint.kilobot_board, built on first use into the user's cache from the C source the package
ships: kilolib started by its RUN message, as on a robot). The board counts
the CPU cycles of each call of ``svm_step``, from its first instruction to its return, and
answers each check the VM makes through its dispatch with the script's row for that step, so
the steps are the script's whatever the controller's sensors read; the actions run as
written. simavr models the AVR's cycle timing and nothing in it depends on the host, so the
counts of one image and script are the same on every run. A CapBot image runs unchanged in
QEMU, its instructions per step counted the same way (footprint_cycles_m4: QEMU models no
cycle timing).

The dispatch a check goes through is one of the functions declared with
``--indirect svm_step=TARGET,...`` (the same declaration the worst-case stack needs; a generated
project's come from its target's record and its sidecar). The script is an event script file,
or the sidecar gen wrote for the image's build, which holds one (swarmvm.footprint.sidecar).
"""

import hashlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from elftools.elf.elffile import ELFFile
from elftools.elf.sections import SymbolTableSection

from ..boundary.errors import ELF_MAX_BYTES, InputError, open_input
from ..compiler.runtime_files import image_format
from ..readers.event_script import parse_script, read_script_rows
from ..boundary.errors import read_input as read_script_bytes
from ..targets import TARGETS
from .cycles_m4 import m4_steps
from .kilobot_board import KilobotToolMissing
from .kilobot_board import run as run_board
from .measure import FootprintError
from .sidecar import SUFFIX, checked, read_sidecar
from .stack import STEP_ROOT

TICKS_PER_STEP_AT_MOST = 64             # kilolib ticks one step may take before the run gives up
TICK_CYCLES = 256 * 1024                # a kilolib tick, in CPU cycles (Timer0 at 8 MHz / 1024, 256 counts)


@dataclass(frozen=True)
class Cycles:
    """Cycles of every step of one run: their mean (rounded to a whole cycle, so a baseline
    compares whole numbers) and the worst step, by number (from 1) and the inputs it was given."""
    script: str
    per_step: tuple[int, ...]
    worst_inputs: tuple[str, ...]
    digest: str = ""            # sha256 of the script's bytes: cycles compare only across one script

    @property
    def mean(self) -> int:
        return (2 * sum(self.per_step) + len(self.per_step)) // (2 * len(self.per_step))

    @property
    def worst(self) -> int:
        return max(self.per_step)

    @property
    def worst_step(self) -> int:
        return self.per_step.index(self.worst) + 1

    def as_json(self) -> dict[str, object]:
        return dict(script=self.script, script_sha256=self.digest, steps=len(self.per_step), mean=self.mean,
                    worst=self.worst, worst_step=self.worst_step, worst_inputs=list(self.worst_inputs))


def _symbols(elf_path: str, names: set[str]) -> dict[str, int]:
    """Addresses of the named functions and objects of an ELF."""
    with open_input(elf_path, ELF_MAX_BYTES) as handle:
        table = ELFFile(handle).get_section_by_name(".symtab")
        if not isinstance(table, SymbolTableSection):
            return {}
        return {s.name: s["st_value"] for s in table.iter_symbols()
                if s.name in names and s["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT")}


def script_masks(script: str, image: bytes, text: str | None = None) -> tuple[list[bytes], list[tuple[str, ...]]]:
    """An event script read against the image's events: each step's event mask (bit e % 8 of
    byte e / 8, at least one byte) and the names of the events in it. ``text``: the script's
    lines, given (a sidecar's), ``script`` the file they come from; else the file ``script``."""
    parsed = image_format().Image.parse(image)
    names = parsed.names or [str(e) for e in range(parsed.num_events)]
    masks, inputs = [], []
    rows = (read_script_rows(script, names, parsed.controllable) if text is None else
            iter(parse_script("%s: script" % script, text, names, parsed.controllable)))
    for row in rows:
        mask = bytearray(max(1, (parsed.num_events + 7) // 8))
        for event in row:
            mask[event // 8] |= 1 << event % 8
        masks.append(bytes(mask))
        inputs.append(tuple("EV_" + names[e] for e in sorted(row)))
    if not masks:
        raise InputError(script, "", "no step in the script: nothing to measure")
    return masks, inputs


def measure_cycles(elf: str, target: str, image: bytes, script: str, dispatch: tuple[str, ...]) -> Cycles:
    """Cycles (Cortex-M4: instructions) of each step of ``elf`` run with ``script``; ``dispatch``:
    the functions svm_step calls through its dispatch pointer (their checks answer from the script).
    A ``script`` named ``*.footprint.json`` is a sidecar (swarmvm.footprint.sidecar), whose script
    is run once it is found to be the sidecar of this image's build (InputError otherwise)."""
    text = None
    if script.endswith(SUFFIX):
        sidecar = checked(read_sidecar(script), elf, target, hashlib.sha256(image).hexdigest())
        text = sidecar.script_text
    masks, inputs = script_masks(script, image, text)
    addresses = _symbols(elf, {STEP_ROOT, "kilo_ticks", *dispatch})
    if STEP_ROOT not in addresses:
        raise FootprintError("%s: no %s in the image: --cycles runs a program that steps the VM" % (elf, STEP_ROOT))
    checks = [addresses[name] for name in dispatch if name in addresses]
    if not dispatch:
        raise FootprintError("%s: --cycles needs the dispatch svm_step calls: declare it with --indirect "
                             "svm_step=NAME,... (target %s declares none)" % (elf, target))
    if not checks:
        raise FootprintError("%s: --cycles needs the dispatch svm_step calls, declared with --indirect svm_step=NAME,... "
                             "(none of %s is in the image)" % (elf, ", ".join(dispatch)))
    record = TARGETS[target].elf
    if record is None or record.emulator not in EMULATORS:
        raise FootprintError("%s: --cycles: no emulator runs target %s's images" % (elf, target))
    per_step = EMULATORS[record.emulator](elf, addresses, checks, masks)
    digest = hashlib.sha256(read_script_bytes(script) if text is None else text.encode("utf-8")).hexdigest()
    return Cycles(script, per_step, inputs[per_step.index(max(per_step))], digest)


def _m4_steps(elf: str, addresses: dict[str, int], checks: list[int], masks: list[bytes]) -> tuple[int, ...]:
    """Instructions of each step of a Cortex-M4 program in QEMU (swarmvm.footprint.cycles_m4)."""
    return m4_steps(elf, addresses[STEP_ROOT], checks, masks)


def _kilobot_steps(elf: str, addresses: dict[str, int], checks: list[int], masks: list[bytes]) -> tuple[int, ...]:
    """CPU cycles of each step of a kilolib program on the simavr Kilobot board."""
    if "kilo_ticks" not in addresses:
        raise FootprintError("%s: no kilo_ticks in the image: --cycles runs a kilolib program that steps the VM" % elf)
    limit = (len(masks) + 2) * TICKS_PER_STEP_AT_MOST * TICK_CYCLES
    try:
        run = run_board(Path(elf), ticks=2 ** 31, cycles=limit, step_pc=addresses[STEP_ROOT], check_pcs=checks,
                        script=masks)
    except KilobotToolMissing as missing:
        raise FootprintError("--cycles: %s" % missing)
    if len(run.steps) < len(masks):
        raise FootprintError("%s: %d of the script's %d steps ran in %d cycles (the run ended: %s)"
                             % (elf, len(run.steps), len(masks), limit, " ".join(map(str, run.end)) or "no end"))
    return tuple(run.steps[:len(masks)])


# What runs a target's images for --cycles, by the name its record gives (targets.record.Elf).
EMULATORS: dict[str, Callable[[str, dict[str, int], list[int], list[bytes]], tuple[int, ...]]] = {
    "kilobot_board": _kilobot_steps, "qemu_m4": _m4_steps}
