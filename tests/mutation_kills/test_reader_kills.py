"""The .xmd and .nza readers (generator/readers/ides_xmd.py, nadzoru_nza.py) pinned where `make mutation`
found them unpinned (issue 29, docs/mutation.md): an element without its id refused naming the
attribute, and an .nza event without ``shared`` private, one with it public."""

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.readers.faudes_gen import read_gen
from swarmvm.readers.nadzoru_nza import read_nza
from swarmvm.readers.ides_xmd import read_xmd
from swarmvm.readers.synth_script import read_synth_script

XMD = '<?xml version="1.0" encoding="UTF-8"?>\n<model type="FSA"><data>%s</data></model>\n'


def test_an_xmd_state_without_an_id_is_refused_naming_the_attribute(tmp_path):
    path = tmp_path / "g.xmd"
    path.write_text(XMD % "<state><properties><initial/></properties></state>")
    with pytest.raises(InputError) as refused:
        read_xmd(str(path))
    assert str(refused.value) == "%s: state: missing attribute id" % path


def test_an_nza_event_is_private_unless_shared(tmp_path):
    path = tmp_path / "g.nza"
    path.write_text('{ ["states"] = { [1] = { ["initial"] = true } }, ["events"] = { '
                    '[1] = { ["name"] = "a", ["controllable"] = true }, '
                    '[2] = { ["name"] = "b", ["controllable"] = false, ["shared"] = true } } }')
    assert read_nza(str(path)).events == {"a": (True, False), "b": (False, True)}


def test_an_nza_state_is_neither_initial_nor_marked_unless_it_says_so(tmp_path):
    """State 1 initial and marked, state 2 neither by default (a second initial state would be
    refused; a marked one would be in ``marked``)."""
    path = tmp_path / "g.nza"
    path.write_text('{ ["states"] = { [1] = { ["initial"] = true, ["marked"] = true }, [2] = { } }, '
                    '["events"] = { [1] = { ["name"] = "a", ["controllable"] = true } }, '
                    '["transitions"] = { [1] = { ["source"] = 1, ["target"] = 2, ["event"] = 1 } } }')
    supervisor = read_nza(str(path)).supervisor
    assert supervisor.initial == 0 and supervisor.marked == frozenset({0}) and len(supervisor.states) == 2


@pytest.mark.parametrize("name, data, load, byte", [("g.nza", b"{ \xff }", read_nza, 2),
                                                    ("g.gen", b"<Generator> \xff", read_gen, 12),
                                                    ("s.txt", b"S = SupC(G, \xff)", lambda path: read_synth_script(path, ()), 12)])
def test_a_file_not_in_utf8_is_refused_naming_the_byte(tmp_path, name, data, load, byte):
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(InputError) as refused:
        load(str(path))
    assert str(refused.value) == "%s: not UTF-8 text (byte %d)" % (path, byte)


def test_an_nza_list_entry_that_is_not_a_table_is_refused_naming_it(tmp_path):
    path = tmp_path / "g.nza"
    path.write_text('{ ["states"] = { [1] = { ["initial"] = true }, [2] = 5 } }')
    with pytest.raises(InputError) as refused:
        read_nza(str(path))
    assert str(refused.value) == "%s: states[2]: expected a table" % path


@pytest.mark.parametrize("value,shown", [("true", "True"), ('"1"', "1"), ("0", "0")])
def test_an_nza_index_must_be_an_integer_in_range(tmp_path, value, shown):
    """A boolean (an int to Python) and a string are refused like an index out of range."""
    path = tmp_path / "g.nza"
    path.write_text('{ ["states"] = { [1] = { ["initial"] = true } }, ["events"] = { [1] = { ["name"] = "a", '
                    '["controllable"] = true } }, ["transitions"] = { [1] = { ["source"] = %s, ["target"] = 1, '
                    '["event"] = 1 } } }' % value)
    with pytest.raises(InputError) as refused:
        read_nza(str(path))
    assert str(refused.value) == "%s: transitions[1].source: expected an index in 1..1, got %s" % (path, shown)


@pytest.mark.parametrize("states", ["5", '{ ["a"] = {} }'])
def test_an_nza_list_that_is_not_a_sequence_is_refused(tmp_path, states):
    path = tmp_path / "g.nza"
    path.write_text('{ ["states"] = %s }' % states)
    with pytest.raises(InputError) as refused:
        read_nza(str(path))
    assert str(refused.value) == "%s: states: expected a list of tables indexed 1..n" % path
