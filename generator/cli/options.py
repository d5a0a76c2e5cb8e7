"""What swarmvm's command lines share in click: the option types, and the main group that ends
every usage error in one line.

click prints a usage error as three lines (``Usage:``, ``Try ... --help``, ``Error: ...``); the
rest of swarmvm ends bad input with one line ``swarmvm: error: ...`` and exit status 2, and
scripts that read stderr expect that form whatever went wrong. :class:`OneLineErrors`, the class
of ``swarmvm``'s main group, turns every usage error of every verb (the studies' included) into
``swarmvm: error: --steps: MESSAGE``: the option's (or argument's) name, then click's message."""

import contextlib
import math
import sys
from typing import Any, Iterator

import click

from ..boundary import terminal
from ..compiler.runtime_files import python_app

SEED_MAX: int = python_app().SEED_MAX   # the VMs' 32-bit seed (runtime_py/swarmvm_app.py); every verb's --seed


class FiniteFloat(click.FloatRange):
    """A float option that must be a number, in the range if one is given. click's ranges let
    nan through (no comparison with it is true), and inf where the range has no top: a density,
    rate or duration of nan or inf makes output that means nothing, divides by it, or runs until
    a time never reached. Refused here with click's own error, exit status 2."""

    name = "float"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> Any:
        number = super().convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail("%s is not a finite number." % value, param, ctx)
        return number

    def _describe_range(self) -> str:
        """The range as ``--help`` shows it: ``finite`` when there is no bound (not ``x<=None``)."""
        return "finite" if self.min is None and self.max is None else super()._describe_range()


# The type of every ``--seed`` option: a negative seed is refused, not folded onto a positive
# one (Python's random) or passed to a generator that raises (numpy's).
SEED = click.IntRange(0, SEED_MAX)


class OneLineUsage(click.UsageError):
    """A usage error already written as swarmvm's one line; click shows it as that line."""

    def show(self, file: Any = None) -> None:
        terminal.error(self.message)


def usage_line(exc: click.UsageError) -> str:
    """The one line for a click usage error: the parameter's name (an option's longest flag, an
    argument's metavar), then click's message without the name it repeats."""
    if isinstance(exc, click.NoSuchOption):
        guesses = " (did you mean %s?)" % ", ".join(exc.possibilities) if exc.possibilities else ""
        return "%s: no such option%s" % (exc.option_name, guesses)
    if isinstance(exc, click.BadOptionUsage):
        return "%s: %s" % (exc.option_name, exc.message)
    if isinstance(exc, click.BadParameter) and exc.param is not None:
        param = exc.param
        name = max(param.opts, key=len) if isinstance(param, click.Option) else param.human_readable_name
        if isinstance(exc, click.MissingParameter):
            choices = param.type.choices if isinstance(param.type, click.Choice) else ()
            return "%s: missing %s%s" % (name, param.param_type_name,
                                         " (one of %s)" % ", ".join(map(str, choices)) if choices else "")
        return "%s: %s" % (name, exc.message)
    return exc.format_message()


# click 8.2 shows the help of a group given no verb as a usage error; that help stays as it is.
_KEPT: tuple[type[Exception], ...] = (OneLineUsage,) + tuple(
    getattr(click.exceptions, name) for name in ("NoArgsIsHelpError",) if hasattr(click.exceptions, name))


@contextlib.contextmanager
def _usage_errors_in_one_line() -> Iterator[None]:
    try:
        yield
    except _KEPT:
        raise
    except click.UsageError as exc:
        raise OneLineUsage(usage_line(exc), exc.ctx) from exc


@contextlib.contextmanager
def _stdout_checked() -> Iterator[None]:
    """What ran printed all it printed: stdout flushed at the end, and a help or version text
    (click prints those itself, then exits) that could not be written, or went to a closed
    stdout, made :class:`terminal.OutputStreamError` like any other line. Every other line goes
    through :mod:`terminal`, so an OSError raised by click's own ``echo`` is that text's; any
    other OSError is left as it is."""
    try:
        yield
    except click.exceptions.Exit:
        if sys.stdout is None:
            raise terminal.OutputStreamError("closed") from None
        terminal.flush()
        raise
    except OSError as exc:
        if _raised_by_click_echo(exc):
            raise terminal.OutputStreamError(exc.strerror or "error") from None
        raise
    terminal.flush()


def _raised_by_click_echo(exc: BaseException) -> bool:
    """The innermost frame of ``exc`` is click's echo (its write of a help or usage text)."""
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    return tb is not None and tb.tb_frame.f_globals.get("__name__") == "click.utils" and (
        tb.tb_frame.f_code.co_name == "echo")


class OneLineErrors(click.Group):
    """The main group: a usage error raised while parsing its own options or running any verb
    below it (parsing that verb's options and arguments included) is printed as one line by
    :func:`usage_line`, exit status 2. ``--help`` and ``--version`` print as usual. Standard
    output that cannot be written ends in one line and status 1 (:func:`terminal.stream_failed`)."""

    def main(self, *args: Any, **kwargs: Any) -> Any:
        try:
            return super().main(*args, **kwargs)
        except terminal.OutputStreamError as exc:
            terminal.stream_failed(exc)

    def make_context(self, info_name: str | None, args: list[str], parent: click.Context | None = None,
                     **extra: Any) -> click.Context:
        with _usage_errors_in_one_line(), _stdout_checked():
            return super().make_context(info_name, args, parent, **extra)

    def invoke(self, ctx: click.Context) -> Any:
        with _usage_errors_in_one_line(), _stdout_checked():
            return super().invoke(ctx)
