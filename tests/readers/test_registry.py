"""The readers' registries (swarmvm.readers): each suffix has one reader, and every reader a
suffix names is fuzzed (tests/fuzz/readers.py), so a new format cannot land unfuzzed."""

import pytest

from fuzz import readers as fuzzed
from swarmvm.boundary.errors import InputError
from swarmvm.readers import READERS, SUPERVISOR_READERS, read_automaton, read_supervisor


def _unfuzzed() -> list[str]:
    """The suffixes whose reader no fuzz target reaches (a target reads one suffix)."""
    registry = {**READERS, **SUPERVISOR_READERS}
    fuzzed_suffixes = {target.suffix for target in fuzzed.READERS.values() if hasattr(target, "suffix")}
    reached = {registry[suffix] for suffix in fuzzed_suffixes if suffix in registry}
    return sorted(suffix for suffix, reader in registry.items() if reader not in reached)


def test_every_reader_in_the_registries_is_fuzzed():
    assert _unfuzzed() == [], "readers no fuzz target of tests/fuzz/readers.py reaches"


def test_a_reader_without_a_fuzz_target_is_seen(monkeypatch):
    monkeypatch.setitem(SUPERVISOR_READERS, ".tbl", lambda path, published: None)
    assert _unfuzzed() == [".tbl"]


def test_the_two_kinds_of_suffix_do_not_overlap():
    assert not set(READERS) & set(SUPERVISOR_READERS)
    assert all(suffix == suffix.lower() and suffix.startswith(".") for suffix in (*READERS, *SUPERVISOR_READERS))


@pytest.mark.parametrize("read", [read_automaton, read_supervisor])
def test_the_dispatchers_refuse_what_no_registry_names(read, tmp_path):
    (tmp_path / "x.tbl").write_text("")
    with pytest.raises(InputError, match="x.tbl"):
        read(str(tmp_path / "x.tbl"))
