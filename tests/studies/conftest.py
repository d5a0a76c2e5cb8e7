"""Shared small configurations for the study tests (short "weeks" keep them fast)."""

import pytest

from swarmvm.studies.drone_delivery.params import Params
from swarmvm.studies.energy_replenishment import plugin


@pytest.fixture
def short():
    """A small fleet, busy orders and 2 reporting periods of 2 hours."""
    return Params(weeks=2, week_s=7200, drones=8, tau_min=5.0, accuracy_samples=50, seed=11)


@pytest.fixture(scope="module")
def library():
    """The energy study's ARGoS plugin, built once (the tests skip without ARGoS)."""
    try:
        plugin.find_argos()
    except plugin.BuildError as exc:
        pytest.skip(str(exc))
    return plugin.build()
