"""What the Kilobot tests need from the machine: avr-gcc and the real kilolib (found, or built
from KILOLIB_SRC into the cache: firmware/kilobot/kilolib_build.py) and the simavr Kilobot board
(firmware/kilobot/board.py). On a user's machine without them a test skips with one line saying
how to get them; in CI (CI=true) it fails instead: nothing Kilobot-related may skip there."""

import os
import sys
from pathlib import Path

import pytest

from checkout import FIRMWARE

sys.path.insert(0, str(Path(FIRMWARE) / "kilobot"))

import board  # noqa: E402
from kilolib_build import KilolibMissing, kilolib_dir  # noqa: E402


def _missing(reason: str):
    if os.environ.get("CI") == "true":
        pytest.fail(reason)
    pytest.skip(reason.splitlines()[0])


def kilolib_or_skip() -> Path:
    """The kilolib folder (kilolib.h, build/kilolib.a)."""
    try:
        return kilolib_dir()
    except KilolibMissing as missing:
        _missing(str(missing))


def board_or_skip() -> Path:
    """The simavr Kilobot board program (and kilolib, which every program it runs links)."""
    kilolib_or_skip()
    try:
        return board.board_path()
    except KilolibMissing as missing:
        _missing(str(missing))
