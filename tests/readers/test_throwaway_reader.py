"""A new input format is one reader module and one READERS entry (docs/extending.md): a
throwaway format, read by a module written to a scratch folder and registered by its suffix,
compiles like any other automaton file and refuses a defect in the words every format shares
(swarmvm.readers.automaton.AutomatonBuilder)."""

import importlib.util

import pytest

from swarmvm import readers
from swarmvm.boundary.errors import InputError
from swarmvm.compiler import pipeline

# A format of lines ``event NAME c|u``, ``state NAME [initial]``, ``edge SOURCE EVENT TARGET``.
READER = '''
"""The throwaway .toy format (tests/readers/test_throwaway_reader.py)."""

from swarmvm.boundary.errors import read_input
from swarmvm.readers.automaton import AutomatonBuilder, AutomatonFile


def read_toy(path: str) -> AutomatonFile:
    raw = read_input(path)
    build = AutomatonBuilder(path)
    for line in raw.decode("ascii").splitlines():
        kind, *words = line.split()
        if kind == "event":
            build.event(words[0], words[0], words[1] == "c")
        elif kind == "state":
            build.state(words[0], words[1:] == ["initial"])
        else:
            build.transition(*words)
    return build.build(len(raw))
'''
FLIPFLOP = "event on c\nevent off c\nstate a initial\nstate b\nedge a on b\nedge b off a\n"


@pytest.fixture
def toy_format(tmp_path, monkeypatch):
    """The reader module imported from the scratch folder and given the suffix .toy: its READERS
    entry, which is all a new entry in the registry's source gives it."""
    (tmp_path / "toy_format.py").write_text(READER)
    spec = importlib.util.spec_from_file_location("toy_format", tmp_path / "toy_format.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    monkeypatch.setitem(readers.READERS, ".toy", module.read_toy)
    return tmp_path


def test_a_throwaway_format_compiles_like_any_automaton_file(toy_format):
    (toy_format / "flipflop.toy").write_text(FLIPFLOP)
    compiled = pipeline.compile_inputs([str(toy_format / "flipflop.toy")])
    assert sorted(compiled.model.events) == ["off", "on"]
    assert compiled.tables.num_states == 2 and compiled.tables.num_transitions == 2
    assert pipeline.compile_inputs([str(toy_format)]).image == compiled.image     # a folder of .toy files too


def test_a_throwaway_format_refuses_in_the_shared_words(toy_format):
    (toy_format / "broken.toy").write_text(FLIPFLOP + "edge a nowhere b\n")
    with pytest.raises(InputError, match="event id nowhere is not declared"):
        pipeline.compile_inputs([str(toy_format / "broken.toy")])


def test_without_its_entry_the_suffix_is_refused(tmp_path):
    (tmp_path / "flipflop.toy").write_text(FLIPFLOP)
    with pytest.raises(InputError, match="not a file swarmvm reads"):
        pipeline.compile_inputs([str(tmp_path / "flipflop.toy")])
