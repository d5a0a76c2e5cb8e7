"""Test-wide set-up: the tests' own modules importable, the ``swarmvm`` command of the Python
running the tests first on PATH (the venv's, or a wheel's install), the reference Python VM."""

import os
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

TESTS = Path(__file__).resolve().parent
sys.path.insert(0, str(TESTS))
os.environ["PATH"] = os.path.dirname(sys.executable) + os.pathsep + os.environ.get("PATH", "")

from swarmvm.compiler.runtime_files import python_vm  # noqa: E402

# Hypothesis (the property tests of tests/properties/ and docs/conformance.md, the generative
# tests of the trust boundary in tests/boundary/, tests/boundary/ and tests/cli/): in CI the same
# few examples every run (derandomized, no example database, no deadline: a compiler may take
# seconds); HYPOTHESIS_PROFILE=long (`make fuzz`) draws many more, at random.
_SLOW_EXAMPLES = [HealthCheck.too_slow, HealthCheck.data_too_large]
settings.register_profile("ci", max_examples=10, derandomize=True, database=None, deadline=None,
                          suppress_health_check=_SLOW_EXAMPLES, print_blob=True)
settings.register_profile("long", max_examples=300, deadline=None, suppress_health_check=_SLOW_EXAMPLES,
                          print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


@pytest.fixture(scope="session")
def vm():
    return python_vm()
