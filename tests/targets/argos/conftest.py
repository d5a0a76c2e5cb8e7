"""Fixtures of the argos-target tests: a real ARGoS (found or built by scripts/argos.sh, the step
`make test` runs first) and the generated controllers built against it.

Without ARGoS and without its source archive the tests skip, saying how to get ARGoS; under
CI=true they fail instead."""

import os

import pytest
from targets.argos.argos_project import CORPUS, NO_ARGOS, build, find_argos, generate


@pytest.fixture(scope="session")
def argos_prefix():
    """The install prefix of a real ARGoS (bin/argos3, include/argos3, lib/argos3)."""
    status, prefix, stderr = find_argos()
    if status == NO_ARGOS and os.environ.get("CI") != "true":
        pytest.skip("ARGoS not found: `make argos` builds it from ARGOS_SRC, or set ARGOS_PREFIX to an ARGoS install")
    assert status == 0, stderr
    return prefix


@pytest.fixture(scope="session")
def energy_worker(argos_prefix, tmp_path_factory):
    """energy_worker's generated controller built with g++, ARGoS given by its prefix:
    (project, build output)."""
    project = generate(CORPUS / "energy_worker.yaml", tmp_path_factory.mktemp("argos_energy_worker"))
    return project, build(project, "g++", "-DARGOS_PREFIX=%s" % argos_prefix)


@pytest.fixture(scope="session")
def network_worker(argos_prefix, tmp_path_factory):
    """network_worker's generated controller built with clang++, ARGoS given by ARGoS_DIR:
    (project, build output)."""
    project = generate(CORPUS / "network_worker.yaml", tmp_path_factory.mktemp("argos_network_worker"))
    return project, build(project, "clang++", "-DARGoS_DIR=%s" % (argos_prefix / "share" / "argos3" / "cmake"))
