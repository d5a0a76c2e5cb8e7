"""Instructions per VM step of a linked CapBot (Cortex-M4F) image, run unchanged in QEMU
(mps2-an386, the machine the bare-metal CapBot build targets) with an event script
(docs/footprint.md, "Cycles per step").

QEMU does not model the Cortex-M4's cycle timing, so the figure is *instructions*, the count
QEMU's ``-icount`` keeps. It is taken through QEMU's GDB stub (qemu_gdb): the program runs at
full speed to a breakpoint at ``svm_step``, then is single-stepped to the call's return
address, one instruction per step of the stub, and the steps are counted. Why not ``-icount``
and a timer read around the call, as the conformance harness does (benchmarks/m4_cycles.py)?
That needs the program to start a timer and read it, which a user's image does not do, and
QEMU 7.2's stub cannot do it for the program: its reads of device registers (SysTick, the
CMSDK timers) return 0 and its writes to them are dropped. Single-stepping needs nothing of
the image but its symbols, and counts exactly: QEMU executes the same instructions whatever
the host, so one image and script give the same counts on every run.

While a step runs, each call of a declared dispatch (``--indirect svm_step=NAME``) for a check
(op ``SVM_OP_CHECK`` in r2, the event in r1) has its return value (r0) replaced, on return, by
the script's bit for that event, so the steps are the script's whatever the program's own checks
say; the actions run as written."""

import shutil
from collections.abc import Sequence

from .measure import FootprintError
from .qemu_gdb import QemuGdb, QemuGdbError

QEMU = ["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
        "-semihosting-config", "enable=on,target=native"]
MAX_STEP_INSTRUCTIONS = 1_000_000       # one step longer than this is taken as one that never returns
OP_CHECK = 0                            # SVM_OP_CHECK (runtime_c/swarmvm.h)
R0, R1, R2, SP, LR, PC = 0, 1, 2, 13, 14, 15


def m4_steps(elf: str, step: int, checks: Sequence[int], masks: Sequence[bytes]) -> tuple[int, ...]:
    """Instructions of each of the first ``len(masks)`` calls of the function at ``step`` in a
    QEMU run of ``elf``, checks entered at ``checks`` answered from ``masks`` (one per step)."""
    if shutil.which(QEMU[0]) is None:
        raise FootprintError("%s: --cycles on a CapBot image runs it in %s, not found" % (elf, QEMU[0]))
    counts: list[int] = []
    try:
        with QemuGdb([*QEMU, "-kernel", elf]) as qemu:
            qemu.breakpoint(step & ~1)
            while len(counts) < len(masks):
                stop = qemu.run()
                if not stop.startswith("T"):
                    raise FootprintError("%s: %d of the script's %d steps ran before the program ended (%s)"
                                         % (elf, len(counts), len(masks), _ending(stop)))
                counts.append(_one_step(qemu, elf, set(c & ~1 for c in checks), masks[len(counts)]))
    except QemuGdbError as exc:
        raise FootprintError("%s: %s" % (elf, exc))
    return tuple(counts)


def _one_step(qemu: QemuGdb, elf: str, checks: set[int], mask: bytes) -> int:
    """Single-step one call from its first instruction to its return; the instructions."""
    back, frame = qemu.register(LR) & ~1, qemu.register(SP)
    pending: tuple[int, int, int] | None = None         # (return address, SP, event) of a check
    count = 0
    while True:
        qemu.request("s")
        count += 1
        pc = qemu.register(PC)
        if pc == back and qemu.register(SP) == frame:
            return count
        if count > MAX_STEP_INSTRUCTIONS:
            raise FootprintError("%s: a step ran past %d instructions without returning" % (elf, MAX_STEP_INSTRUCTIONS))
        if pending is None and pc in checks and qemu.register(R2) == OP_CHECK:
            pending = (qemu.register(LR) & ~1, qemu.register(SP), qemu.register(R1))
        elif pending is not None and pc == pending[0] and qemu.register(SP) == pending[1]:
            event = pending[2]
            qemu.set_register(R0, (mask[event // 8] >> event % 8) & 1 if event // 8 < len(mask) else 0)
            pending = None


def _ending(stop: str) -> str:
    """A stop reply that is not a breakpoint, in words: ``W2a`` -> exit status 42."""
    if stop.startswith("W"):
        return "exit status %d" % int(stop[1:].split(";")[0], 16)
    return "stopped: %s" % stop
