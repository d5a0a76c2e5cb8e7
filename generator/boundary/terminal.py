"""Every line swarmvm's command lines print, in one place: the compiler's verbs and the studies'.

What they print holds other people's text: file and model names, keys of a supervisor file,
paths, event names, option values typed on the command line. A file name holding a newline, an
ESC sequence or a bidirectional override, printed as it is, could clear the screen or forge a
second ``swarmvm: error:`` line. Each function here escapes what it prints with
:func:`swarmvm.boundary.escape.terminal`, so a message is one line and the terminal gets only text.

Messages go to stderr as ``swarmvm: KIND: MESSAGE`` (:func:`error`, :func:`warn`, :func:`note`);
results go to stdout (:func:`line` for one line, :func:`lines` for a report of several).

Standard output that cannot take a line (a full device, a closed stream, a pipe whose reader
has gone) is :class:`OutputStreamError`: the command line ends it in one line and status 1
(:func:`stream_failed`), never a traceback, and never exit 0 with the output lost."""

import errno
import os
import sys
from typing import NoReturn

import click

from .escape import MESSAGE_LINE_LIMIT, bounded, terminal


def message(kind: str, text: object) -> None:
    """``swarmvm: KIND: TEXT`` as one line on stderr."""
    click.echo("swarmvm: %s: %s" % (kind, bounded(terminal(str(text)), MESSAGE_LINE_LIMIT)), err=True)


def error(text: object) -> None:
    """``swarmvm: error: TEXT`` on stderr (bad input; the caller exits with status 2)."""
    message("error", text)


def warn(text: object) -> None:
    """``swarmvm: warning: TEXT`` on stderr (the input is used, but something in it is ignored)."""
    message("warning", text)


def note(text: object) -> None:
    """``swarmvm: note: TEXT`` on stderr (what a verb left out, and why)."""
    message("note", text)


def fail(text: object, status: int = 2) -> NoReturn:
    """:func:`error`, then exit with ``status`` (2: bad input; 1: the work itself failed)."""
    error(text)
    sys.exit(status)


class OutputStreamError(Exception):
    """Standard output cannot be written: ``reason`` says why (its strerror, or "closed")."""

    def __init__(self, reason: str) -> None:
        super().__init__("standard output: cannot write (%s)" % reason)
        self.reason = reason


def _stdout_failure(exc: OSError) -> OutputStreamError:
    return OutputStreamError(exc.strerror or errno.errorcode.get(exc.errno or 0, "error"))


def line(text: object) -> None:
    """``text`` as one line on stdout: a line break in it (a file name's, say) is escaped too.
    OutputStreamError when stdout cannot take it (Python leaves sys.stdout None when the
    process started with it closed; click.echo would then drop the line silently)."""
    if sys.stdout is None:
        raise OutputStreamError("closed")
    try:
        click.echo(terminal(str(text)))
    except OSError as exc:
        raise _stdout_failure(exc) from None


def flush() -> None:
    """Flush stdout, so that a failure to write what is buffered is seen before the process
    ends (Python would otherwise report it at exit, after the status is decided)."""
    if sys.stdout is not None:
        try:
            sys.stdout.flush()
        except OSError as exc:
            raise _stdout_failure(exc) from None


def stream_failed(exc: OutputStreamError) -> NoReturn:
    """End the process for a stdout failure: one line on stderr (where it can be written) and
    status 1; stdout is pointed at the null device first, so that the interpreter's own flush
    at exit finds nothing more to fail on."""
    if sys.stdout is not None:
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError):
            pass
    try:
        message("error", exc)
    except (OSError, ValueError):
        pass
    sys.exit(1)


def lines(text: str) -> None:
    """A report of several lines on stdout, as :func:`line` prints each of its ``\\n``-separated
    lines (other line breaks, ``\\r`` included, are escaped)."""
    for each in text.split("\n"):
        line(each)
