"""The footprint tests' images (footprint_images.py), built once per session."""

import pytest

from footprint_images import build_deeper, build_estimate, build_float, build_images, build_larger, build_slower


@pytest.fixture(scope="session")
def build(tmp_path_factory):
    root = tmp_path_factory.mktemp("footprint")
    build_images(root)
    return root


@pytest.fixture(scope="session")
def larger(build, tmp_path_factory):
    """The Kilobot energy_worker with a larger controller (footprint_images.BALLAST)."""
    return build_larger(build, tmp_path_factory.mktemp("larger") / "energy_worker")


@pytest.fixture(scope="session")
def deeper(build, tmp_path_factory):
    """The Kilobot energy_worker with a big local array in a check (footprint_images.DEEPER)."""
    return build_deeper(build, tmp_path_factory.mktemp("deeper") / "energy_worker")


@pytest.fixture(scope="session")
def slower(build, tmp_path_factory):
    """The Kilobot energy_worker with a busy-waiting check (footprint_images.SLOWER)."""
    return build_slower(build, tmp_path_factory.mktemp("slower") / "energy_worker")


@pytest.fixture(scope="session")
def floating(build, tmp_path_factory):
    """The Kilobot energy_worker with float arithmetic in a check (footprint_images.FLOAT)."""
    return build_float(build, tmp_path_factory.mktemp("float") / "energy_worker")


@pytest.fixture(scope="session")
def estimating(build, tmp_path_factory):
    """The Kilobot energy_worker with a check calling kilolib's estimate_distance() (footprint_images.ESTIMATE)."""
    return build_estimate(build, tmp_path_factory.mktemp("estimate") / "energy_worker")
