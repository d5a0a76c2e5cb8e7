"""mypy checks the whole package and the Python runtime with --strict (issue 39): pyproject.toml's
[tool.mypy] says ``strict = true`` over generator/ and runtime_py/, and no override turns a strict
flag off for a module, so that loosening `make typecheck` (which runs mypy over that
configuration) fails here rather than silently."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# mypy --strict's flags that a per-module section could set back to their loose value.
STRICT_FLAGS = {
    "disallow_untyped_defs": True, "disallow_incomplete_defs": True, "check_untyped_defs": True,
    "disallow_any_generics": True, "disallow_subclassing_any": True, "disallow_untyped_decorators": True,
    "disallow_untyped_calls": True, "warn_return_any": True, "implicit_reexport": False, "strict_equality": True,
    "extra_checks": True, "no_implicit_reexport": True, "warn_unused_ignores": True,
}
# What an override may say: where third-party or installed-only modules have no stubs.
ALLOWED_OVERRIDES = {"module", "ignore_missing_imports"}


def _mypy() -> dict[str, object]:
    config: dict[str, object] = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["mypy"]
    return config


def test_the_whole_package_and_runtime_are_strict() -> None:
    mypy = _mypy()
    assert mypy.get("strict") is True
    files = mypy["files"]
    assert isinstance(files, list) and set(files) == {"generator", "runtime_py"}


def test_no_override_loosens_a_module() -> None:
    overrides = _mypy().get("overrides", [])
    assert isinstance(overrides, list)
    loosening = [(section["module"], sorted(set(section) - ALLOWED_OVERRIDES)) for section in overrides
                 if set(section) - ALLOWED_OVERRIDES]
    assert loosening == [], "overrides set flags other than ignore_missing_imports: %s" % loosening


def test_no_top_level_flag_undoes_strict() -> None:
    mypy = _mypy()
    undone = {flag: mypy[flag] for flag, value in STRICT_FLAGS.items() if flag in mypy and mypy[flag] != value}
    assert not undone, "[tool.mypy] sets strict flags back: %s" % undone
