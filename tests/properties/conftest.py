"""Hypothesis profiles of the property tests (docs/conformance.md), here rather than in the
suite's conftest so that the rest of the suite runs without hypothesis (the installed-wheel
check runs part of it in a venv with pytest alone)."""

import os

from hypothesis import HealthCheck, settings

# Property tests (tests/properties/, docs/conformance.md): in CI the same few examples every run
# (derandomized, no example database, no deadline: a compiler may take seconds); locally
# HYPOTHESIS_PROFILE=long draws many more, at random.
_SLOW_EXAMPLES = [HealthCheck.too_slow, HealthCheck.data_too_large]
settings.register_profile("ci", max_examples=10, derandomize=True, database=None, deadline=None,
                          suppress_health_check=_SLOW_EXAMPLES, print_blob=True)
settings.register_profile("long", max_examples=300, deadline=None, suppress_health_check=_SLOW_EXAMPLES,
                          print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
