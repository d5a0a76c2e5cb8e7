"""Test-wide fixtures: paths to the vendored corpus and the reference Python VM."""

import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
sys.path.insert(0, str(TESTS))

from swarmvm.runtime import python_vm  # noqa: E402


@pytest.fixture(scope="session")
def vm():
    return python_vm()
