"""The one error type for bad input: a single line naming file, key and place.

The CLI prints it as ``swarmvm: error: <line>`` and exits with status 2; nothing is written."""

import os

from .escape import terminal

MAX_BYTES = 1 << 20   # no real supervisor comes near it (the corpus's largest is 11 kB)


class InputError(Exception):
    """Bad input. ``where`` names the supervisor / state / event concerned, if any."""

    def __init__(self, file, key, message, where=""):
        super().__init__(message)
        self.file, self.key, self.where, self.message = file, key, where, message

    def __str__(self):
        parts = [self.file, self.key, self.where, self.message]
        return ": ".join(terminal(part) for part in parts if part)


def ascii_int(text, digits=9):
    """``text`` as a non-negative integer when it is 1 to ``digits`` ASCII digits, else None.
    The bound comes before ``int()``, which accepts other scripts' digits ('²' passes
    ``isdigit`` and fails ``int``) and refuses strings of over 4,300 digits with a ValueError."""
    if not 0 < len(text) <= digits or not (text.isascii() and text.isdigit()):
        return None
    return int(text)


def read_input(path):
    """The bytes of an input file, refusing one that cannot be read or is over MAX_BYTES. At most
    MAX_BYTES + 1 bytes are read: a device or pipe (``/dev/zero``) has no size to check first."""
    try:
        size = os.path.getsize(path)
        if size > MAX_BYTES:
            raise InputError(path, "", "file is %d bytes, over the %d-byte limit" % (size, MAX_BYTES))
        with open(path, "rb") as handle:
            data = handle.read(MAX_BYTES + 1)
        if len(data) > MAX_BYTES:
            raise InputError(path, "", "file is over the %d-byte limit" % MAX_BYTES)
        return data
    except OSError as exc:
        raise InputError(path, "", "cannot read file (%s)" % exc.strerror)
