"""Test-wide set-up: the tests' own modules importable, the ``swarmvm`` command of the Python
running the tests first on PATH (the venv's, or a wheel's install), the reference Python VM."""

import os
import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
sys.path.insert(0, str(TESTS))
os.environ["PATH"] = os.path.dirname(sys.executable) + os.pathsep + os.environ.get("PATH", "")

from swarmvm.runtime import python_vm  # noqa: E402


@pytest.fixture(scope="session")
def vm():
    return python_vm()
