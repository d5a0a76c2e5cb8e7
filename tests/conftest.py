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


# `make test` runs the suite on every core (pytest-xdist, `--dist loadgroup`). A module's tests
# stay together on one worker, so its module-scoped fixtures are built once; the folders whose
# session-scoped fixtures build images or projects (the footprint images, the ARGoS controllers)
# are one group each, so they are built once too. Those long groups are collected first: handed
# out last, one of them would end the run alone on one core.
_SHARED_FIXTURE_FOLDERS = ("footprint", "targets/argos")


def _group(item: pytest.Item) -> str:
    """The xdist group of a test: its shared-fixture folder, else its module's path."""
    path = item.path.relative_to(TESTS).as_posix()
    return next((folder for folder in _SHARED_FIXTURE_FOLDERS if path.startswith(folder + "/")), path)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        item.add_marker(pytest.mark.xdist_group(_group(item)))
    items.sort(key=lambda item: _group(item) not in _SHARED_FIXTURE_FOLDERS)
