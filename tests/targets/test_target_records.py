"""Every target of the package passes the target-generic checks (target_checks.py), the same the
throwaway target passes (test_throwaway_target.py), and its record is what the registry holds."""

import pytest

from swarmvm.targets import TARGETS, target_modules
from target_checks import check_docs_page, check_refuses_names_as_the_others, check_renders_deterministically


def test_the_registry_holds_the_record_of_every_target_module():
    records = [m.TARGET for m in target_modules() if hasattr(m, "TARGET")]
    assert {r.name: r for r in records} == TARGETS
    assert sorted(TARGETS) == ["argos", "c", "capbot", "kilobot", "pipuck", "python"]


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_renders_deterministically(target, tmp_path):
    check_renders_deterministically(TARGETS[target], tmp_path)


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_refuses_names_as_the_others(target, tmp_path):
    check_refuses_names_as_the_others(TARGETS[target], tmp_path)


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_has_its_docs_page(target):
    check_docs_page(TARGETS[target])
