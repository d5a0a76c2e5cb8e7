"""The argument checks of swarmvm's Python API (:mod:`swarmvm.api`), in one place.

Each public function of the API names a rule per parameter with :func:`checked`; the rules run
on the bound arguments before the function does any work. The policy (docs/api.md, "Errors"):

- an argument of the wrong type is a mistake in the calling program: :class:`TypeError`
  (``compile_model("x.yaml")``, a str where a list of paths is expected, would otherwise read
  one file per character; a ``pathlib.Path`` where a str is expected; ``True`` as a count);
- an argument of the right type whose value the function cannot use is bad input, as if typed
  on the command line: :class:`~swarmvm.boundary.errors.InputError` naming the parameter (an empty list
  of files, a count out of range, nan, an unknown target, format or mode, a file name holding
  NUL). What is wrong inside a file stays the readers' InputError, as before.

So a program that passes its user's values through can print ``str(exc)`` of an InputError as
the command line does, and a TypeError always means the program itself must change."""

import functools
import inspect
import math
from collections.abc import Sequence
from typing import Any, Callable, Iterable, TypeVar, cast

from .errors import InputError, verb_scope

F = TypeVar("F", bound=Callable[..., Any])
Rule = Callable[[str, Any], None]


def checked(**rules: Rule) -> Callable[[F], F]:
    """Decorator: before the function runs, each argument (as bound to the function's
    signature, defaults included) is checked by its rule in ``rules``. Every parameter must have
    one: a parameter added without a rule fails at import, not in a user's hands."""
    def decorate(function: F) -> F:
        signature = inspect.signature(function)
        if set(rules) != set(signature.parameters):
            raise TypeError("%s: rules for %s, parameters %s" % (function.__name__, ", ".join(sorted(rules)),
                                                                  ", ".join(signature.parameters)))

        @functools.wraps(function)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            for name, rule in rules.items():
                rule(name, bound.arguments[name])
            with verb_scope():          # what this call reads, no output of it may replace
                return function(*args, **kwargs)
        return cast(F, wrapper)
    return decorate


def _type_error(name: str, expected: str, value: Any) -> TypeError:
    return TypeError("%s: expected %s, got %s" % (name, expected, type(value).__name__))


def text(name: str, value: Any) -> None:
    """A str (a model name, a source label)."""
    if not isinstance(value, str):
        raise _type_error(name, "a str", value)


def file_name(name: str, value: Any) -> None:
    """A file or folder name: a str, not empty, without NUL (which no file name can hold; the
    operating system's calls would raise ValueError)."""
    text(name, value)
    if not value:
        raise InputError("", name, "an empty file name")
    if "\0" in value:
        raise InputError(value, name, "a file name cannot hold NUL")


def _sequence(name: str, value: Any, item: Rule) -> None:
    """A list or tuple (not a str, whose characters would be taken as items), each item ``item``."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
        raise _type_error(name, "a list of str", value)
    for index, each in enumerate(value):
        item("%s[%d]" % (name, index), each)


def file_names(name: str, value: Any) -> None:
    """A list or tuple of at least one file name (:func:`file_name`)."""
    _sequence(name, value, file_name)
    if not value:
        raise InputError("", name, "no file given")


def maybe_file_names(name: str, value: Any) -> None:
    """A list or tuple of file names, possibly empty (the traces of ``inspect``)."""
    (file_names if value else texts)(name, value)


def texts(name: str, value: Any) -> None:
    """A list or tuple of str, possibly empty (repeatable options: statements, exports)."""
    _sequence(name, value, text)


def flag(name: str, value: Any) -> None:
    """A bool."""
    if not isinstance(value, bool):
        raise _type_error(name, "a bool", value)


def optional(rule: Rule) -> Rule:
    """``rule``, or None."""
    def check(name: str, value: Any) -> None:
        if value is not None:
            rule(name, value)
    return check


def instance(kind: type | tuple[type, ...], expected: str) -> Rule:
    """An instance of ``kind`` (described as ``expected`` in the error)."""
    def check(name: str, value: Any) -> None:
        if not isinstance(value, kind):
            raise _type_error(name, expected, value)
    return check


def integer(low: int, high: int | None = None) -> Rule:
    """An int (not a bool) from ``low`` to ``high`` (no upper bound when None)."""
    def check(name: str, value: Any) -> None:
        if isinstance(value, bool) or not isinstance(value, int):
            raise _type_error(name, "an int", value)
        if value < low or (high is not None and value > high):
            bounds = "from %d to %d" % (low, high) if high is not None else "at least %d" % low
            raise InputError("", name, "must be %s, got %d" % (bounds, value))
    return check


def number(low: float, high: float) -> Rule:
    """A finite int or float (not a bool) in [low, high]; nan passes no comparison, so it is
    refused by name."""
    def check(name: str, value: Any) -> None:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _type_error(name, "a float", value)
        if not (math.isfinite(value) and low <= value <= high):
            raise InputError("", name, "must be a finite number from %g to %g, got %r" % (low, high, value))
    return check


def one_of(choices: Iterable[str], what: str) -> Rule:
    """A str among ``choices`` (a target, a format, a mode); ``what`` names it in the error."""
    known = tuple(sorted(choices))

    def check(name: str, value: Any) -> None:
        text(name, value)
        if value not in known:
            raise InputError("", name, "unknown %s %r (one of %s)" % (what, value, ", ".join(known)))
    return check
