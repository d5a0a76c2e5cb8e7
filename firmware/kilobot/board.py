"""Run a real-kilolib Kilobot image on simavr's ATmega328P, with the IR channel of
``firmware/kilobot/board/kilobot_board.c`` (what the board models, and what it does not, is in
that file's first lines). Used by the Kilobot tests, the swap demo and ``make kilobot-board``.

The program starts as on a real Kilobot: kilolib boots into its idle state and the board sends
the overhead controller's RUN message over IR (``start_tick``), which makes kilolib run setup()
and then loop(). The board is built once per source version into the user's cache, like kilolib.

    python3 firmware/kilobot/board.py      prints the board program's path (building it if need be)
"""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from kilolib_build import KilolibMissing, cache_root, print_path  # noqa: E402

SOURCE = Path(__file__).resolve().parent / "board" / "kilobot_board.c"
SIMAVR_INCLUDE = Path("/usr/include/simavr")
RUN = 0x88              # kilolib message.h: the overhead controller's "run the program"
NORMAL = 0
TICK_CYCLES = 256 * 1024            # kilolib's Timer0: compare match every 256 counts at 8 MHz / 1024
SRAM_OFFSET = 0x800000              # avr-gcc's address of SRAM in ELF symbols
RAMEND = 0x8FF                      # the ATmega328P's last SRAM address, where the stack starts


def board_path() -> Path:
    """The built board program (cache/kilobot_board-<source hash>), compiled once."""
    digest = hashlib.sha256(SOURCE.read_bytes()).hexdigest()[:12]
    target = cache_root() / ("kilobot_board-%s" % digest)
    if target.is_file():
        return target
    if shutil.which("cc") is None or not (SIMAVR_INCLUDE / "sim_avr.h").is_file():
        raise KilolibMissing("kilobot board: needs a C compiler and simavr's headers (Debian: libsimavr-dev; "
                             "scripts/setup.sh installs them)")
    target.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=target.parent) as work:
        built = Path(work) / target.name
        result = subprocess.run(["cc", "-std=c99", "-D_DEFAULT_SOURCE", "-O2", "-Wall", "-Wextra", "-Werror",
                                 "-I%s" % SIMAVR_INCLUDE, "-I%s" % (SIMAVR_INCLUDE / "avr"), str(SOURCE),
                                 "-lsimavr", "-o", str(built)], capture_output=True, text=True)
        if result.returncode != 0:
            raise KilolibMissing("kilobot board: build failed:\n" + result.stderr)
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
    lines: list = field(default_factory=list)
    rx: list = field(default_factory=list)
    tx: list = field(default_factory=list)
    collisions: int = 0
    leds: list = field(default_factory=list)        # (tick, set_color value) on each change
    end: tuple = ()
    ram: int | None = None                          # the ``read`` variable at the end
    stack: int | None = None                        # bytes of stack used at most (``paint_stack``)
    eeprom: bytes = b""


def _message(fields: list) -> Message:
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
        elif tag == "#end":
            run.end = (int(fields[1]), int(fields[2]), fields[3])
        else:
            run.lines.append(line)
    return run


def run(elf: Path, ticks: int | None, messages=(), start_tick: int = 1, eeprom: bytes | None = None,
        read: str | None = None, paint_stack: bool = False, timeout: int = 600) -> Run:
    """Run ``elf`` until kilo_ticks reaches ``ticks`` (None: until the image stops the CPU, for
    programs without kilolib, which get no messages). ``messages``: (tick, type, 9 data bytes),
    sent in order once kilo_ticks reaches their tick, after the RUN message at ``start_tick``;
    ``eeprom``: the EEPROM's contents from address 0 (default: erased, 0xFF); ``read``: a 4-byte
    variable whose value at the end is ``Run.ram``; ``paint_stack``: SRAM above the static data
    (``_end``) is painted before the run and ``Run.stack`` is the deepest the stack reached."""
    elf = Path(elf)
    with tempfile.TemporaryDirectory() as work:
        schedule = Path(work) / "schedule"
        rows = [(start_tick, RUN, bytes(9))] + sorted(messages, key=lambda m: m[0])
        schedule.write_text("".join("%d %02x %s\n" % (t, k, bytes(d).ljust(9, b"\0").hex()) for t, k, d in rows))
        command = [str(board_path()), "-m", str(schedule), "-E", str(Path(work) / "eeprom.out")]
        if ticks is not None:
            command += ["-t", str(sram_symbol(elf, "kilo_ticks")), "-n", str(ticks)]
        if read is not None:
            command += ["-r", str(sram_symbol(elf, read))]
        if paint_stack:
            command += ["-s", str(sram_symbol(elf, "_end"))]
        if eeprom is not None:
            (Path(work) / "eeprom.in").write_bytes(eeprom)
            command += ["-e", str(Path(work) / "eeprom.in")]
        proc = subprocess.run(command + [str(elf)], capture_output=True, text=True, timeout=timeout)
        if proc.returncode != 0:
            raise RuntimeError("kilobot board failed on %s: %s" % (elf, proc.stderr.strip()))
        result = parse(proc.stdout)
        result.eeprom = (Path(work) / "eeprom.out").read_bytes()
    return result


if __name__ == "__main__":
    sys.exit(print_path(board_path))
