"""The one error type for bad input: a single line naming file, key and place.

The CLI prints it as ``swarmvm: error: <line>`` and exits with status 2; nothing is written."""

import contextlib
import os
import stat
from contextvars import ContextVar
from typing import BinaryIO, Iterator, Optional

from .escape import bounded, terminal

MAX_BYTES = 1 << 20   # no real supervisor comes near it (the corpus's largest is 11 kB)
# A linked firmware image the footprint readers measure (an ELF with its debugging sections): the
# CapBot's is 215 kB, an ARGoS controller library a few MB; a larger file is not a robot's image.
ELF_MAX_BYTES = 64 << 20
# A compiler's stack-usage file (.su), one line per function: the runtime's largest is 3 kB.
SU_MAX_BYTES = MAX_BYTES
# One trial's table of a study's sweep (Parquet): the largest trial the studies accept (10,000,000
# accuracy cells, docs/limits.md) writes well under it.
TABLE_MAX_BYTES = 1 << 30


class InputError(Exception):
    """Bad input. ``where`` names the supervisor / state / event concerned, if any."""

    def __init__(self, file: str, key: str, message: str, where: str = "") -> None:
        super().__init__(message)
        self.file, self.key, self.where, self.message = file, key, where, message

    def __str__(self) -> str:
        """One line, each part escaped for a terminal and cut to MESSAGE_PART_LIMIT characters."""
        parts = [self.file, self.key, self.where, self.message]
        return ": ".join(bounded(terminal(part)) for part in parts if part)


def ascii_int(text: str, digits: int = 9) -> Optional[int]:
    """``text`` as a non-negative integer when it is 1 to ``digits`` ASCII digits, else None.
    The bound comes before ``int()``, which accepts other scripts' digits ('²' passes
    ``isdigit`` and fails ``int``) and refuses strings of over 4,300 digits with a ValueError."""
    if not 0 < len(text) <= digits or not (text.isascii() and text.isdigit()):
        return None
    return int(text)


def file_kind(mode: int) -> str:
    """What a file of ``mode`` is, as a phrase ("a folder", "a character device")."""
    for test, phrase in ((stat.S_ISDIR, "a folder"), (stat.S_ISREG, "a regular file"),
                         (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                         (stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return phrase
    return "an unknown kind of file"


# The files (device, inode) and folders read in the current verb (None outside one): the output
# layer refuses to replace one of them, so that `pack x.yaml -o x.yaml` cannot lose the source.
_READ: ContextVar[Optional[set[tuple[int, int]]]] = ContextVar("swarmvm_inputs_read", default=None)


@contextlib.contextmanager
def verb_scope() -> Iterator[None]:
    """The reads of one verb, or one call of the API, however many functions it calls: the
    outermost scope starts an empty record (per thread and task, as a context variable)."""
    token = _READ.set(set()) if _READ.get() is None else None
    try:
        yield
    finally:
        if token is not None:
            _READ.reset(token)


def note_read(info: os.stat_result) -> None:
    """Record a file or folder (its stat) as read by the current verb."""
    read = _READ.get()
    if read is not None:
        read.add((info.st_dev, info.st_ino))


def was_read(info: os.stat_result) -> bool:
    """The file or folder of ``info`` was read by the current verb."""
    read = _READ.get()
    return read is not None and (info.st_dev, info.st_ino) in read


def open_input(path: str, limit: Optional[int] = None, record: bool = True) -> BinaryIO:
    """An input file opened for reading, the one way every reader opens one: refused (InputError)
    when it cannot be opened, is not a regular file (a FIFO, a device, a folder, a socket:
    opened without waiting for a writer, refused, never read) or, with ``limit``, is over that
    many bytes. The file is recorded as read by the current verb (:func:`note_read`) unless
    ``record`` is false."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise InputError(path, "", "cannot read file (%s)" % exc.strerror)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(path, "", "is %s, not a regular file" % file_kind(info.st_mode))
        if limit is not None and info.st_size > limit:
            raise InputError(path, "", "file is %d bytes, over the %d-byte limit" % (info.st_size, limit))
        handle = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    if record:
        note_read(info)
    return handle


def read_input(path: str, edit: bool = False, limit: int = MAX_BYTES) -> bytes:
    """The bytes of an input file (:func:`open_input`), at most ``limit`` of them (MAX_BYTES,
    or a kind's own bound: ELF_MAX_BYTES for a linked image, docs/limits.md): at most
    ``limit`` + 1 bytes are read, so a file that grows while it is read is refused too.
    ``edit``: the verb reads the file to replace it (``compat-switch`` edits a project's build
    files in place), so it is not recorded as an input the output layer must keep."""
    with open_input(path, limit, record=not edit) as handle:
        try:
            data = handle.read(limit + 1)
        except OSError as exc:
            raise InputError(path, "", "cannot read file (%s)" % exc.strerror)
    if len(data) > limit:
        raise InputError(path, "", "file is over the %d-byte limit" % limit)
    return data


def decode_text(file: str, data: bytes, key: str = "", of: str = "") -> str:
    """``data`` decoded as UTF-8, or InputError naming ``file``, ``key`` and the first bad byte
    (``of`` says what the byte's number counts in: " of the line"). Every reader of text says
    it in these words, so a test or a user sees one message whatever the format."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(file, key, "not UTF-8 text (byte %d%s)" % (exc.start, of))
