"""mypy checks the core with its strict options (issue 28): pyproject.toml's strict override lists
every core module and sets every strict flag, so that dropping a module or a flag fails here
rather than silently loosening `make typecheck` (which runs mypy over that configuration)."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# The modules issue 28 names and the compiler's stages around them: loading, the model, the
# tables, the image, rendering, the targets, and the Python runtime's format and VM.
CORE = {
    "generator.readers.automaton", "generator.compiler.canonical", "generator.compiler.image", "generator.readers.supervisor_yaml",
    "generator.readers.lua_literal", "generator.compiler.model", "generator.compiler.naming", "generator.compiler.pipeline", "generator.readers.faudes_gen",
    "generator.readers.nadzoru_nza", "generator.readers.ides_xmd", "generator.compiler.render", "generator.compiler.tables", "generator.targets.values",
    "generator.targets", "runtime_py.swarmvm_format", "runtime_py.swarmvm_vm",
}

# mypy --strict's flags that a per-module section may set, each at its strict value.
STRICT_FLAGS = {
    "disallow_untyped_defs": True, "disallow_incomplete_defs": True, "check_untyped_defs": True,
    "disallow_any_generics": True, "disallow_subclassing_any": True, "disallow_untyped_decorators": True,
    "warn_return_any": True, "implicit_reexport": False, "strict_equality": True, "extra_checks": True,
}


def _strict_overrides() -> list[dict[str, object]]:
    mypy = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["mypy"]
    return [section for section in mypy.get("overrides", []) if "disallow_untyped_defs" in section]


def _strict_modules() -> set[str]:
    modules: set[str] = set()
    for section in _strict_overrides():
        listed = section["module"]
        modules.update([listed] if isinstance(listed, str) else listed)
    return modules


def test_every_core_module_is_strict() -> None:
    missing = CORE - _strict_modules()
    assert not missing, "core modules not under mypy's strict options in pyproject.toml: %s" % sorted(missing)


def test_the_strict_override_sets_every_strict_flag() -> None:
    sections = _strict_overrides()
    assert sections, "pyproject.toml has no strict [[tool.mypy.overrides]] section"
    for section in sections:
        wrong = {flag: section.get(flag) for flag, value in STRICT_FLAGS.items() if section.get(flag) != value}
        assert not wrong, "strict override for %s: flags not at their strict value: %s" % (section["module"], wrong)


def test_every_strict_module_exists() -> None:
    """mypy ignores an override naming no module: a misspelt name would check nothing."""
    def has_file(name: str) -> bool:
        path = ROOT / name.replace(".", "/")
        return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()

    absent = sorted(name for name in _strict_modules() if not has_file(name))
    assert not absent, "strict override names modules that have no file: %s" % absent
