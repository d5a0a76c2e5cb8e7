"""tests/ mirrors the package (issue 39): a subpackage of generator/ without a test folder of its
name, a target without its folder under tests/targets/, or a folder tests/README.md's tables do
not list is a newcomer's dead end, so each fails here."""

import re
from pathlib import Path

from swarmvm.targets import TARGETS

TESTS = Path(__file__).resolve().parents[1]
GENERATOR = TESTS.parent / "generator"
TARGETS_TESTED_ELSEWHERE = {"python": "tests/python"}     # the Python runtime's own target


def _listed_folders() -> set[str]:
    """Every `tests/<folder>/` named in the first column of tests/README.md's tables."""
    listed = set()
    for line in (TESTS / "README.md").read_text().splitlines():
        if line.startswith("| `tests/"):
            listed.update(re.findall(r"`(tests/[\w/]+)/`", line.split(" | ")[0]))
    return listed


def test_every_subpackage_has_a_test_folder_of_its_name():
    subpackages = {p.parent.name for p in GENERATOR.glob("*/__init__.py")}
    assert subpackages, "no subpackage found under generator/"
    missing = sorted(name for name in subpackages if not (TESTS / name).is_dir())
    assert not missing, f"subpackages of generator/ without a tests/<name>/ folder: {missing}"


def test_every_target_has_a_test_folder():
    missing = sorted(name for name in TARGETS
                     if name not in TARGETS_TESTED_ELSEWHERE and not (TESTS / "targets" / name).is_dir())
    assert not missing, f"targets without a tests/targets/<name>/ folder: {missing}"
    for folder in TARGETS_TESTED_ELSEWHERE.values():
        assert (TESTS.parent / folder).is_dir(), folder


def test_every_test_folder_is_listed_in_the_readme():
    folders = {f"tests/{p.name}" for p in TESTS.iterdir() if p.is_dir() and not p.name.startswith((".", "__"))}
    folders |= {f"tests/targets/{p.name}" for p in (TESTS / "targets").iterdir()
                if p.is_dir() and p.name != "throwaway" and not p.name.startswith("__")}
    unlisted = sorted(folders - _listed_folders())
    assert not unlisted, f"folders tests/README.md's tables do not list: {unlisted}"
    gone = sorted(name for name in _listed_folders() if not (TESTS.parent / name).is_dir())
    assert not gone, f"tests/README.md lists folders that are not there: {gone}"
