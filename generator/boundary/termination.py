"""SIGTERM, the stop a job scheduler, `timeout` or a service manager sends, ends a verb the way an
exception does, so that what the verb started is stopped and removed on the way out: a child it
runs (ARGoS, simavr, QEMU, a compiler) is killed by :func:`subprocess.run`, temporary folders are
deleted, and output being written is rolled back (boundary/output.py holds the signal while it commits,
then delivers it here). Then the signal is raised again with its default action, so that the
process ends by SIGTERM as before, as its parent expects. Left to the default action from the
start, the process ended at once and its ARGoS child ran on, orphaned, with its temporary folder."""

from __future__ import annotations

import signal
import threading
from types import FrameType
from typing import Callable


class Terminated(SystemExit):
    """Raised by SIGTERM in the verb: unwinds it (SystemExit: no handler of ordinary exceptions
    takes it for an error of its own)."""


def end_verbs_on_sigterm() -> Callable[[], None]:
    """Installs the handler (main thread, when SIGTERM has its default action); returns what puts
    the previous one back and, when SIGTERM came, raises it again to end the process."""
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGTERM) != signal.SIG_DFL:
        return lambda: None
    received: list[int] = []

    def terminated(signum: int, frame: FrameType | None) -> None:
        received.append(signum)
        raise Terminated(128 + signum)

    previous = signal.signal(signal.SIGTERM, terminated)

    def restore() -> None:
        signal.signal(signal.SIGTERM, previous)
        if received:
            signal.raise_signal(signal.SIGTERM)
    return restore
