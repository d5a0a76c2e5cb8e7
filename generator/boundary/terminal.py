"""Every line swarmvm's command lines print, in one place: the compiler's verbs and the studies'.

What they print holds other people's text: file and model names, keys of a supervisor file,
paths, event names, option values typed on the command line. A file name holding a newline, an
ESC sequence or a bidirectional override, printed as it is, could clear the screen or forge a
second ``swarmvm: error:`` line. Each function here escapes what it prints with
:func:`swarmvm.boundary.escape.terminal`, so a message is one line and the terminal gets only text.

Messages go to stderr as ``swarmvm: KIND: MESSAGE`` (:func:`error`, :func:`warn`, :func:`note`);
results go to stdout (:func:`line` for one line, :func:`lines` for a report of several)."""

import sys
from typing import NoReturn

import click

from .escape import terminal


def message(kind: str, text: object) -> None:
    """``swarmvm: KIND: TEXT`` as one line on stderr."""
    click.echo("swarmvm: %s: %s" % (kind, terminal(str(text))), err=True)


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


def line(text: object) -> None:
    """``text`` as one line on stdout: a line break in it (a file name's, say) is escaped too."""
    click.echo(terminal(str(text)))


def lines(text: str) -> None:
    """A report of several lines on stdout, as :func:`line` prints each of its ``\\n``-separated
    lines (other line breaks, ``\\r`` included, are escaped)."""
    for each in text.split("\n"):
        line(each)
