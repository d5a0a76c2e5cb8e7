"""A Kilobot on simavr's ATmega328P: runs a real-kilolib Kilobot image with the IR channel of
``kilobot_board.c`` beside this file (what the board models, and what it does not, is in that
file's first lines). Used by ``swarmvm footprint --cycles`` (an installed swarmvm ships the C
source as package data and builds the board on first use), the Kilobot tests, the swap demo
and ``make kilobot-board`` (firmware/kilobot/board.py).

The program starts as on a real Kilobot: kilolib boots into its idle state and the board sends
the overhead controller's RUN message over IR (``start_tick``), which makes kilolib run setup()
and then loop(). The board is built once per source version into the user's cache
(``${XDG_CACHE_HOME:-~/.cache}/swarmvm/``), where kilolib is built too."""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from ...targets.kilobot import KILOBOT_MESSAGE_BYTES

SOURCE = resources.files(__name__) / "kilobot_board.c"
SIMAVR_INCLUDE = Path("/usr/include/simavr")
RUN = 0x88              # kilolib message.h: the overhead controller's "run the program"
NORMAL = 0
TICK_CYCLES = 256 * 1024            # kilolib's Timer0: compare match every 256 counts at 8 MHz / 1024
SRAM_OFFSET = 0x800000              # avr-gcc's address of SRAM in ELF symbols
RAMEND = 0x8FF                      # the ATmega328P's last SRAM address, where the stack starts


class KilobotToolMissing(RuntimeError):
    """A tool the Kilobot images or the board need (kilolib, avr-gcc, a C compiler, simavr's
    headers) is missing or failed to build; the message says how to get it."""


def cache_root() -> Path:
    """Where built tools are kept: the user's cache folder, never the checkout."""
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "swarmvm"


def board_path() -> Path:
    """The built board program (cache/kilobot_board-<source hash>), compiled once."""
    source = SOURCE.read_bytes()
    target = cache_root() / ("kilobot_board-%s" % hashlib.sha256(source).hexdigest()[:12])
    if target.is_file():
        return target
    if shutil.which("cc") is None or not (SIMAVR_INCLUDE / "sim_avr.h").is_file():
        raise KilobotToolMissing("kilobot board: needs a C compiler and simavr's headers (Debian: apt install gcc "
                                 "libsimavr-dev)")
    target.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=target.parent) as work:
        built, copy = Path(work) / target.name, Path(work) / "kilobot_board.c"
        copy.write_bytes(source)
        result = subprocess.run(["cc", "-std=c99", "-D_DEFAULT_SOURCE", "-O2", "-Wall", "-Wextra", "-Werror",
                                 "-I%s" % SIMAVR_INCLUDE, "-I%s" % (SIMAVR_INCLUDE / "avr"), str(copy),
                                 "-lsimavr", "-o", str(built)], capture_output=True, text=True)
        if result.returncode != 0:
            raise KilobotToolMissing("kilobot board: build failed:\n" + result.stderr)
        built.rename(target)
    return target


def sram_symbol(elf: Path, name: str) -> int:
    """The SRAM address of a data symbol of ``elf`` (avr-nm)."""
    out = subprocess.run(["avr-nm", str(elf)], check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[2] == name:
            return int(parts[0], 16) - SRAM_OFFSET
    raise KeyError("%s: no symbol %s" % (elf, name))


@dataclass
class Message:
    tick: int
    type: int
    data: bytes
    ok: bool = True


@dataclass
class Run:
    """What one run showed: the image's USART0 lines, the messages sent to the robot (``rx``)
    and by it (``tx``), collisions, where it ended (kilo_ticks, cycles, why) and the EEPROM."""
    lines: list[str] = field(default_factory=list)
    rx: list[Message] = field(default_factory=list)
    tx: list[Message] = field(default_factory=list)
    collisions: int = 0
    leds: list[tuple[int, int]] = field(default_factory=list)        # (tick, set_color value) on each change
    end: tuple[int, int, str] | tuple[()] = ()
    ram: int | None = None                          # the ``read`` variable at the end
    stack: int | None = None                        # bytes of stack used at most (``paint_stack``)
    steps: list[int] = field(default_factory=list)  # cycles of each svm_step call (``step_pc``)
    eeprom: bytes = b""


def _message(fields: list[str]) -> Message:
    return Message(int(fields[1]), int(fields[2], 16), bytes.fromhex(fields[3]), fields[4:] != ["badcrc"])


def parse(output: str) -> Run:
    run = Run()
    for line in output.splitlines():
        fields = line.split()
        tag = fields[0] if line.startswith("#") and fields else None
        if tag == "#rx":
            run.rx.append(_message(fields))
        elif tag == "#tx":
            run.tx.append(_message(fields))
        elif tag == "#led":
            run.leds.append((int(fields[1]), int(fields[2])))
        elif tag == "#collision":
            run.collisions += 1
        elif tag == "#stack":
            run.stack = RAMEND + 1 - int(fields[1])
        elif tag == "#ram":
            run.ram = int(fields[2])
        elif tag == "#step":
            run.steps.append(int(fields[2]))
        elif tag == "#end":
            run.end = (int(fields[1]), int(fields[2]), fields[3])
        else:
            run.lines.append(line)
    return run


def run(elf: Path, ticks: int | None, messages: Iterable[tuple[int, int, bytes]] = (), start_tick: int = 1,
        eeprom: bytes | None = None, read: str | None = None, paint_stack: bool = False, timeout: int = 600,
        cycles: int | None = None, step_pc: int | None = None, check_pcs: Iterable[int] = (),
        script: Iterable[bytes] | None = None) -> Run:
    """Run ``elf`` until kilo_ticks reaches ``ticks`` (None: until the image stops the CPU, for
    programs without kilolib, which get no messages). ``messages``: (tick, type, 9 data bytes),
    sent in order once kilo_ticks reaches their tick, after the RUN message at ``start_tick``;
    ``eeprom``: the EEPROM's contents from address 0 (default: erased, 0xFF); ``read``: a 4-byte
    variable whose value at the end is ``Run.ram``; ``paint_stack``: SRAM above the static data
    (``_end``) is painted before the run and ``Run.stack`` is the deepest the stack reached;
    ``cycles``: stop after this many CPU cycles; ``step_pc``: svm_step's address, ``Run.steps``
    the cycles of each call; ``script``: rows of event-mask bytes, one per step, that checks
    entered at ``check_pcs`` (functions svm_step calls through its dispatch) answer instead of
    the program, the run ending when the step after the last row begins."""
    elf = Path(elf)
    with tempfile.TemporaryDirectory() as work:
        schedule = Path(work) / "schedule"
        rows = [(start_tick, RUN, bytes(KILOBOT_MESSAGE_BYTES))] + sorted(messages, key=lambda m: m[0])
        schedule.write_text("".join("%d %02x %s\n" % (t, k, bytes(d).ljust(KILOBOT_MESSAGE_BYTES, b"\0").hex())
                                    for t, k, d in rows))
        command = [str(board_path()), "-m", str(schedule), "-E", str(Path(work) / "eeprom.out")]
        if ticks is not None:
            command += ["-t", str(sram_symbol(elf, "kilo_ticks")), "-n", str(ticks)]
        if read is not None:
            command += ["-r", str(sram_symbol(elf, read))]
        if paint_stack:
            command += ["-s", str(sram_symbol(elf, "_end"))]
        if cycles is not None:
            command += ["-c", str(cycles)]
        if step_pc is not None:
            command += ["-p", str(step_pc)] + [a for pc in check_pcs for a in ("-k", str(pc))]
        if script is not None:
            (Path(work) / "script").write_text("".join(bytes(row).hex() + "\n" for row in script))
            command += ["-x", str(Path(work) / "script")]
        if eeprom is not None:
            (Path(work) / "eeprom.in").write_bytes(eeprom)
            command += ["-e", str(Path(work) / "eeprom.in")]
        proc = subprocess.run(command + [str(elf)], capture_output=True, text=True, timeout=timeout)
        if proc.returncode != 0:
            raise RuntimeError("kilobot board failed on %s: %s" % (elf, proc.stderr.strip()))
        result = parse(proc.stdout)
        result.eeprom = (Path(work) / "eeprom.out").read_bytes()
    return result
