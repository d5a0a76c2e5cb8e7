"""Write generated output as a transaction: afterwards the destination holds all the new files
or all the old ones, never a mix, and none of swarmvm's own temporary or backup files.

:func:`write_outputs` works in three steps:

1. **check**, changing nothing: no destination may be, or lie below, a symbolic link; a folder
   on the way must be a folder; a file to be written must be absent or a regular file (a folder,
   a device, a FIFO or a socket is refused, never replaced), and neither a file the command read
   (same device and inode: a hard link or another spelling of the path is the same file) nor
   in a folder of inputs it read (:func:`swarmvm.boundary.errors.note_read`). A file marked ``keep`` (a controller
   skeleton the user edits) is left alone when it is a regular file.
2. **stage**: make the missing folders, write each file to a new temporary file beside its
   destination (``.swarmvm-*``, fsynced), and reserve a backup name beside each destination
   that exists. A failure or an interrupt here removes everything staged.
   A new file's permissions are what the umask leaves of ``rw-rw-rw-``; a replaced file keeps
   its own.
3. **commit**: move each file being replaced aside to its backup, rename the new one in, and
   only when all are in delete the backups. A failure here puts back what was replaced and
   removes what was added (and the folders staging made, when empty).

SIGINT and SIGTERM are held while output is written: in staging, one ends the staging at the
next file operation (and what was staged is removed); in the commit and the roll-back it waits
until they are done. Then the signal is delivered again to the handler installed before (the
default ones: KeyboardInterrupt for SIGINT, the process ended by SIGTERM). The handlers are
installed only when called from the main thread; called from another thread, nothing is held
(Python delivers signals to the main thread only, so they do not interrupt the write).

Every file operation goes through :data:`OPS` (a :class:`FileOps`), the seam that
tests/boundary/test_output_faults.py wraps to make the k-th operation fail."""

import os
import signal
import stat
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path
from types import FrameType
from typing import Any, Mapping

from .errors import InputError, file_kind, was_read

TEMPORARY_PREFIX = ".swarmvm-"
HELD_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class FileOps:
    """The file operations output makes, one method each: the seam fault injection wraps."""

    def mkdir(self, path: str) -> None:
        os.mkdir(path)

    def rmdir(self, path: str) -> None:
        os.rmdir(path)

    def open(self, folder: str) -> tuple[int, str]:
        """A new, empty file in ``folder`` that no other file can have been: (descriptor, path)."""
        return tempfile.mkstemp(dir=folder, prefix=TEMPORARY_PREFIX)

    def write(self, fd: int, data: bytes) -> None:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]

    def fsync(self, fd: int) -> None:
        os.fsync(fd)

    def chmod(self, fd: int, mode: int) -> None:
        os.fchmod(fd, mode)

    def close(self, fd: int) -> None:
        os.close(fd)

    def rename(self, source: str, destination: str) -> None:
        os.replace(source, destination)

    def unlink(self, path: str) -> None:
        os.unlink(path)


OPS = FileOps()


class _Failed(Exception):
    """A file operation failed on behalf of ``destination`` (a real output path, never a
    temporary one)."""

    def __init__(self, destination: str, operation: str, error: OSError):
        super().__init__(destination)
        self.destination, self.operation = destination, operation
        self.reason = "%s: %s" % (operation, error.strerror or error)


class _Interrupted(Exception):
    """A held signal ended the staging."""


class _HeldSignals:
    """While in its ``with``: SIGINT and SIGTERM recorded, not acted on; on leaving, the first
    one is delivered again to the handler that was there before (main thread only)."""

    def __init__(self) -> None:
        self.pending: int | None = None
        self._previous: dict[int, Any] = {}

    def __enter__(self) -> "_HeldSignals":
        if threading.current_thread() is threading.main_thread():
            for signum in HELD_SIGNALS:
                if signal.getsignal(signum) not in (signal.SIG_IGN, None):
                    self._previous[signum] = signal.signal(signum, self._hold)
        return self

    def _hold(self, signum: int, frame: FrameType | None) -> None:
        if self.pending is None:
            self.pending = signum

    def __exit__(self, *exc_info: object) -> None:
        for signum, previous in self._previous.items():
            signal.signal(signum, previous)
        if self.pending is not None:
            signal.raise_signal(self.pending)


@dataclass
class _Staged:
    """One file on its way: its temporary file, the backup name reserved for the file it
    replaces (None: it adds one), and how far the commit got."""
    destination: str
    temporary: str = ""
    backup: str | None = None
    moved_aside: bool = False
    placed: bool = False


class _Transaction:
    """The staged files and made folders of one write, and how to commit or undo them."""

    def __init__(self, signals: _HeldSignals):
        self.signals = signals
        self.folders: list[str] = []          # made by staging, in the order made
        self.staged: list[_Staged] = []

    def _do(self, destination: str, operation: str, *args: Any) -> Any:
        try:
            return getattr(OPS, operation)(*args)
        except OSError as exc:
            raise _Failed(destination, operation, exc) from None

    def _stage_step(self, destination: str, operation: str, *args: Any) -> Any:
        """One operation of staging, after ending the staging if a signal came."""
        if self.signals.pending is not None:
            raise _Interrupted()
        return self._do(destination, operation, *args)

    def stage(self, destination: Path, data: bytes) -> None:
        missing = []
        folder = destination.parent
        while not os.path.lexists(folder):
            missing.append(folder)
            folder = folder.parent
        for folder in reversed(missing):
            self._stage_step(str(folder), "mkdir", str(folder))
            self.folders.append(str(folder))
        staged = _Staged(str(destination))
        # A replaced file keeps its permissions; a new one gets what the umask leaves of rw-rw-rw-,
        # as any program's new file does (the temporary file is made 0600 whatever the umask).
        mode = stat.S_IMODE(os.lstat(destination).st_mode) if os.path.lexists(destination) else 0o666 & ~umask()
        if os.path.lexists(destination):
            fd, staged.backup = self._stage_step(staged.destination, "open", str(destination.parent))
            self.staged.append(staged)
            self._do(staged.destination, "close", fd)
        else:
            self.staged.append(staged)
        fd, staged.temporary = self._stage_step(staged.destination, "open", str(destination.parent))
        try:
            self._stage_step(staged.destination, "write", fd, data)
            self._stage_step(staged.destination, "fsync", fd)
            self._stage_step(staged.destination, "chmod", fd, mode)
        finally:
            self._do(staged.destination, "close", fd)

    def commit(self) -> None:
        for staged in self.staged:
            if staged.backup is not None:
                self._do(staged.destination, "rename", staged.destination, staged.backup)
                staged.moved_aside = True
            self._do(staged.destination, "rename", staged.temporary, staged.destination)
            staged.placed = True

    def drop_backups(self) -> list[tuple[str, str]]:
        """Delete the replaced files' backups; those that could not be: (destination, phrase)."""
        left = []
        for staged in self.staged:
            if staged.backup is not None:
                try:
                    self._do(staged.destination, "unlink", staged.backup)
                except _Failed as exc:
                    left.append((staged.destination, "%s remains (%s)" % (os.path.basename(staged.backup), exc.reason)))
        return left

    def undo(self) -> list[str]:
        """Put back what the commit replaced, remove what staging added; what could not be
        undone, one phrase each."""
        left = []
        for staged in reversed(self.staged):
            steps: list[tuple[str, ...]] = []
            if staged.moved_aside:
                steps.append(("rename", staged.backup or "", staged.destination))
            elif staged.placed:
                steps.append(("unlink", staged.destination))
            elif staged.backup is not None:
                steps.append(("unlink", staged.backup))
            if staged.temporary and not staged.placed:
                steps.append(("unlink", staged.temporary))
            for operation, *args in steps:
                try:
                    self._do(staged.destination, operation, *args)
                except _Failed as exc:
                    left.append("%s (%s)" % (staged.destination, exc.reason))
        for folder in reversed(self.folders):
            try:
                self._do(folder, "rmdir", folder)
            except _Failed as exc:
                left.append("%s (%s)" % (folder, exc.reason))
        return left


_UMASK_LOCK = threading.Lock()


def umask() -> int:
    """The process's umask, read without changing it where the system says it (Linux's
    /proc/self/status); elsewhere set and put back under a lock, so that no two threads of
    swarmvm race on it."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _UMASK_LOCK:
        current = os.umask(0o022)
        os.umask(current)
    return current


def write_outputs(outdir: str | Path, files: Mapping[str, tuple[bytes, bool]], option: str = "-o") -> list[str]:
    """Write ``files`` ({path relative to ``outdir``: (bytes, keep)}) into ``outdir`` as one
    transaction (this module's docstring); the paths written, sorted. A destination refused,
    a failed operation or an interrupt in staging is an InputError naming the real destination
    (``option`` is the key it reports: the command-line option that named it)."""
    outdir = Path(outdir)
    plan = [(outdir / rel, data) for rel, (data, keep) in sorted(files.items())
            if _to_be_written(outdir, Path(rel), keep, option)]
    with _HeldSignals() as signals:
        transaction = _Transaction(signals)
        try:
            for destination, data in plan:
                transaction.stage(destination, data)
            transaction.commit()
        except BaseException as exc:
            left = transaction.undo()
            unrestored = "; not undone: %s" % ", ".join(left) if left else ""
            if isinstance(exc, _Failed):
                raise InputError(exc.destination, option, "cannot write (%s)%s" % (exc.reason, unrestored)) from None
            if isinstance(exc, _Interrupted):
                name = signal.Signals(signals.pending or signal.SIGINT).name
                raise InputError(str(outdir), option, "interrupted by %s: nothing written%s" % (name, unrestored)) from None
            raise
        kept = transaction.drop_backups()
        if kept:
            raise InputError(kept[0][0], option, "written, but the copy of the file it replaced could not be "
                             "deleted: %s" % "; ".join(phrase for _, phrase in kept))
    return [str(destination) for destination, _ in plan]


def _to_be_written(outdir: Path, rel: Path, keep: bool, option: str) -> bool:
    """Whether ``outdir / rel`` is to be written (False: a kept user file that exists); an
    InputError when it may not be. Checked without following links: ``outdir``, the folders
    below it and the file itself must not be one (a link planted there would send the output
    elsewhere); the folders must be folders; the file must be absent or a regular file. A kept
    file may be a link to the user's file: it is read, never written."""
    if keep and (outdir / rel).is_file():
        return False
    for depth in range(len(rel.parts) + 1):
        path = outdir.joinpath(*rel.parts[:depth])
        try:
            info = os.lstat(path)
        except FileNotFoundError:
            return True
        except OSError as exc:
            raise InputError(str(path), option, "cannot write (lstat: %s)" % exc.strerror)
        mode = info.st_mode
        if stat.S_ISLNK(mode):
            raise InputError(str(path), option, "is a symbolic link: swarmvm does not write through or over one")
        if depth < len(rel.parts) and not stat.S_ISDIR(mode):
            raise InputError(str(path), option, "is %s, not a folder" % file_kind(mode))
        if depth == len(rel.parts) and not stat.S_ISREG(mode):
            raise InputError(str(path), option, "is %s, not a file that can be written" % file_kind(mode))
        if depth == len(rel.parts) and was_read(info):
            raise InputError(str(path), option, "is an input of this command: writing it would replace what was "
                             "read; give another output")
        if depth == len(rel.parts) - 1 and was_read(info):
            raise InputError(str(path), option, "is a folder of inputs this command read: writing into it would "
                             "change what it holds; give another output")
    return True
