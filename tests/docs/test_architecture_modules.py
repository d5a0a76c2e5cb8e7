"""docs/architecture.md names every module of generator/ and every file of the three runtimes
(issue 39, point 5): it is where a newcomer reads why each one exists, so a module added without
its line there fails here, and so does a line naming a file that moved or went away.

A file is named by its path from the checkout's root in backquotes (`generator/compiler/tables.py`,
`runtime_c/swarmvm.h`), the one spelling every page uses, so a file's name cannot match another
file of the same name in another subpackage; a pattern (`runtime_c/swarmvm_learn.*`,
`generator/targets/<name>.py`) names none."""

from __future__ import annotations

import re
from pathlib import Path

from checkout import ROOT

PAGE = ROOT / "docs" / "architecture.md"
FOLDERS = ("generator", "runtime_py", "runtime_c", "runtime_cpp")
NAMED = re.compile(r"`((?:%s)/[^`\s*<>{}]+)`" % "|".join(FOLDERS))


def source_files(root: Path) -> set[str]:
    """Every file of FOLDERS under ``root``, as a path from ``root``, without Python's caches."""
    return {path.relative_to(root).as_posix() for folder in FOLDERS for path in (root / folder).rglob("*")
            if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc"}


def named(text: str) -> set[str]:
    """The paths of FOLDERS a page names in backquotes."""
    return set(NAMED.findall(text))


def exists(root: Path, path: str) -> bool:
    """A named file is a file; a named folder (`generator/readers/`) a folder."""
    return (root / path).is_dir() if path.endswith("/") else (root / path).is_file()


def test_the_page_names_every_module_and_runtime_file():
    missing = sorted(source_files(ROOT) - named(PAGE.read_text()))
    assert missing == [], "docs/architecture.md does not name (as `path`, with a line on why it is separate): %s" \
        % ", ".join(missing)


def test_every_file_the_page_names_exists():
    stale = sorted(path for path in named(PAGE.read_text()) if not exists(ROOT, path))
    assert stale == [], "docs/architecture.md names files that do not exist: %s" % ", ".join(stale)


def test_a_module_left_unnamed_or_a_stale_name_is_found(tmp_path):
    for path in ("generator/api.py", "generator/readers/new_format.py", "generator/readers/__pycache__/x.pyc",
                 "runtime_c/swarmvm.h", "runtime_py/swarmvm_vm.py"):
        (tmp_path / path).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / path).write_text("")
    page = ("`generator/api.py` the API; `runtime_c/swarmvm.h` the C VM; `runtime_py/swarmvm_vm.py`; "
            "`generator/readers/old_format.py` moved; `runtime_c/swarmvm_learn.*` a group; `generator/readers/`; "
            "`generator/inspector/` gone; `generator/readers/<format>.py`")
    assert sorted(source_files(tmp_path) - named(page)) == ["generator/readers/new_format.py"]
    assert sorted(p for p in named(page) if not exists(tmp_path, p)) == ["generator/inspector/",
                                                                          "generator/readers/old_format.py"]
