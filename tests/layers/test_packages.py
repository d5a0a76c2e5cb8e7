"""Every Python package of the source folders is one the wheel installs: setuptools takes only the
packages pyproject.toml's ``[tool.setuptools] packages`` lists, so a subpackage left out of it
(``generator/readers/`` when it was new) works in a checkout and an editable install and is
missing from the wheel, where ``import swarmvm.readers`` fails."""

import tomllib
from pathlib import Path

from imports import ROOT


def _setuptools() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]


def installed_packages(folder: Path, name: str) -> list[str]:
    """The packages under ``folder`` (itself included: each folder holding an ``__init__.py``),
    named as installed with ``folder`` as package ``name``."""
    return sorted(".".join((name, *init.parent.relative_to(folder).parts)) for init in folder.rglob("__init__.py"))


def unlisted(package_dir: dict[str, str], packages: list[str], root: Path) -> list[str]:
    """The packages of every folder of ``package_dir`` ({package: folder}) that ``packages``
    does not list."""
    listed = set(packages)
    return [package for name, folder in sorted(package_dir.items())
            for package in installed_packages(root / folder, name) if package not in listed]


def test_every_package_of_the_source_folders_is_listed():
    config = _setuptools()
    assert unlisted(config["package-dir"], config["packages"], ROOT) == []
    # the compiler's subpackages are among those checked
    assert {"swarmvm.readers", "swarmvm.footprint.kilobot_board"} <= set(installed_packages(ROOT / "generator", "swarmvm"))


def test_a_package_left_out_of_the_list_is_found(tmp_path):
    for folder in ("pkg", "pkg/listed", "pkg/new/deeper"):
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
        (tmp_path / folder / "__init__.py").write_text("")
    (tmp_path / "pkg" / "new" / "data").mkdir()           # a folder without __init__.py is no package
    found = unlisted({"top": "pkg"}, ["top", "top.listed"], tmp_path)
    assert found == ["top.new.deeper"]                    # "pkg/new" itself holds no __init__.py
    assert unlisted({"top": "pkg"}, ["top", "top.listed", "top.new.deeper"], tmp_path) == []
