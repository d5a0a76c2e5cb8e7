"""Readers of Nadzoru's .nza, IDES .xmd and libFAUDES .gen: the same automaton in every format
gives the same canonical model, every verb takes them, and each malformed file gets one
line naming file, key and place, exit status 2 and no output."""

from pathlib import Path

import pytest

from models.model_cases import SYNTHESIS, run
from swarmvm.readers.lua_literal import LuaSyntaxError, parse_lua_table
from swarmvm.compiler.pipeline import compile_inputs

DATA = Path(__file__).resolve().parent / "data"
G1 = [SYNTHESIS / "G1.xml", SYNTHESIS / "G1.nza", DATA / "G1.xmd", DATA / "G1.gen"]


def test_the_same_plant_in_four_formats_is_the_same_model():
    models = [compile_inputs([str(p)]).model for p in G1]
    assert all(m.events == ("charge", "moveToCharge", "moveToWork", "work") for m in models)
    assert all(m.controllable == (True,) * 4 for m in models)
    assert len({m.supervisors for m in models}) == 1


@pytest.mark.parametrize("name", ["E1", "E2", "E3", "E4", "G1", "G2", "G3"])
def test_every_nza_of_the_corpus_equals_its_xml(name):
    assert compile_inputs([str(SYNTHESIS / (name + ".nza"))]).model.supervisors == \
        compile_inputs([str(SYNTHESIS / (name + ".xml"))]).model.supervisors


@pytest.mark.parametrize("path", G1[1:], ids=lambda p: p.suffix)
def test_every_verb_takes_the_new_formats(path, tmp_path):
    assert run("check", path).exit_code == 0
    assert run("pack", path, "-o", tmp_path / "g.svm").exit_code == 0
    assert run("gen", path, "--target", "python", "-o", tmp_path / "py").exit_code == 0
    script = run("script", path, "--steps", "5")
    assert script.exit_code == 0
    (tmp_path / "s.txt").write_text(script.stdout)
    trace = run("trace", path, "--script", tmp_path / "s.txt")
    assert trace.exit_code == 0 and trace.stdout.splitlines()[0].startswith("1 EV_moveToWork ")
    assert run("export", path, "-f", "yaml", "-o", tmp_path / "g.yaml").exit_code == 0
    assert run("check", "--properties", path).exit_code == 0
    assert run("equiv", path, SYNTHESIS / "G1.xml").exit_code == 0


def test_several_files_of_mixed_formats_form_one_set(tmp_path):
    result = run("check", SYNTHESIS / "G2.nza")
    assert result.exit_code == 0
    model = compile_inputs([str(SYNTHESIS / "G1.nza"), str(DATA / "G1.xmd"), str(SYNTHESIS / "G3.xml")]).model
    assert len(model.supervisors) == 3


NZA_G = '{ ["states"] = { [1] = { ["initial"] = true, ["marked"] = true } }, ["events"] = { [1] = { ["name"] = "a", ["controllable"] = true } }, ["transitions"] = { [1] = { ["source"] = 1, ["target"] = 1, ["event"] = 1 } } }'
XMD_HEAD = '<?xml version="1.0" encoding="UTF-8"?>\n'
MALFORMED = [
    ("nza", 'os.execute("rm -rf /")', "line 1: not a Lua table literal: unexpected character '.'"),
    ("nza", 'print("x")', "line 1: not a Lua table literal: unexpected character '('"),
    ("nza", 'x', "line 1: not a Lua table literal: expected a table constructor '{', found 'x'"),
    ("nza", '{ ["states"] = loadstring }', "line 1: not a Lua table literal: expected a value, found 'loadstring'"),
    ("nza", "{ a = 1,\n b = 2 + 3 }", "line 2: not a Lua table literal: unexpected character '+'"),
    ("nza", '{ ["states"] = { [1] = { ["initial"] = true } }', "line 1: not a Lua table literal: expected ',' or '}', found end of file"),
    ("nza", '{ a = 1, a = 2 }', "line 1: not a Lua table literal: key 'a' given twice"),
    ("nza", NZA_G.replace('["target"] = 1', '["target"] = 2'), "transitions[1].target: expected an index in 1..1, got 2"),
    ("nza", NZA_G.replace('["initial"] = true', '["initial"] = 1'), "states[1].initial: expected true or false, got 1"),
    ("nza", NZA_G.replace('"a"', '"a b"'), "events[1]: event 1: 'a b' is not an event name (at most 255 letters, digits and '_')"),
    ("nza", NZA_G.replace('["initial"] = true', '["initial"] = false'), "states: no initial state"),
    ("nza", NZA_G.replace('["states"] = {', '["states"] = { [3] = {}, '), "states: expected a list of tables indexed 1..n"),
    ("xmd", XMD_HEAD + '<!DOCTYPE m [<!ENTITY x "y">]><model type="FSA"><data/></model>', "a DOCTYPE or entity declaration is not accepted"),
    ("xmd", XMD_HEAD + '<model type="FSA"><data>', "not valid XML: no element found: line 2, column 24"),
    ("xmd", XMD_HEAD + '<model type="Petri"/>', 'model: expected <model type="FSA"> at the top, got <model>'),
    ("xmd", XMD_HEAD + '<model type="FSA"><data><state id="1"><properties><initial/></properties></state>'
                       '<transition id="1" source="1" target="1"/></data></model>',
     "transition: transition 1: a transition without an event is not supported"),
    ("xmd", XMD_HEAD + '<model type="FSA"><data><state id="1"><properties><initial/></properties></state>'
                       '<state id="2"><properties><initial/></properties></state></data></model>',
     "state: state 2: a second initial state"),
    ("xmd", XMD_HEAD + '<model type="FSA"><data><state id="1"><properties><initial/></properties></state>'
                       '<event id="1"><properties/><name>u</name></event>'
                       '<transition id="1" source="1" target="9" event="1"/></data></model>',
     "transition: state 1, event EV_u: state id 9 is not declared"),
    ("xml", XMD_HEAD + '<!DOCTYPE model [<!ENTITY lol "lol">]><model type="FSA"><data/></model>',
     "a DOCTYPE or entity declaration is not accepted"),
    ("gen", "<Alphabet> a </Alphabet>", "Generator: expected <Generator> at the top"),
    ("gen", "<Generator> <Alphabet> a </Alphabet>", "Generator: missing </Generator>"),
    ("gen", "<Generator> <Alphabet> a\n</Generator>", "Alphabet: line 1: section is not closed"),
    ("gen", "<Generator> <Foo> </Foo> </Generator>", "Foo: line 1: unexpected '<Foo>' (expected one of Alphabet, "
                                                     "States, TransRel, InitStates, MarkedStates)"),
    ("gen", "<Generator> <Alphabet> a </Alphabet> <States> 1 2 </States> <TransRel> 1 a </TransRel> "
            "<InitStates> 1 </InitStates> </Generator>", "TransRel: expected triples: source event target"),
    ("gen", "<Generator> <Alphabet> a </Alphabet> <States> 1 2 </States> <TransRel> 1 a 2 1 a 1 </TransRel> "
            "<InitStates> 1 </InitStates> </Generator>", "TransRel: state 1, event EV_a: nondeterministic: a second "
                                                          "transition on this event"),
    ("gen", "<Generator> <Alphabet> a </Alphabet> <States> 1 2 </States> <TransRel> 1 b 2 </TransRel> "
            "<InitStates> 1 </InitStates> </Generator>", "TransRel: state 1: event id b is not declared"),
    ("gen", "<Generator> <Alphabet> a </Alphabet> <States> 1 2 </States> <InitStates> 1 2 </InitStates> "
            "</Generator>", "InitStates: 2 initial states; a supervisor has one"),
    ("gen", "<Generator> <Alphabet> a </Alphabet> <States> 1 </States> <MarkedStates> 7 </MarkedStates> "
            "<InitStates> 1 </InitStates> </Generator>", "MarkedStates: state 7 is not in States"),
    ("gen", "<Generator> <Alphabet> a.b </Alphabet> </Generator>",
     "Alphabet: event a.b: 'a.b' is not an event name (at most 255 letters, digits and '_')"),
    ("gen", "<Generator> <States> 1 </States> </Generator>", "InitStates: no initial state"),
    ("gen", "<Generator>\n% swarmvm public: z\n<Alphabet> a </Alphabet> </Generator>",
     "swarmvm public: event z is not in the Alphabet"),
]


@pytest.mark.parametrize("suffix,text,message", MALFORMED, ids=lambda v: v if isinstance(v, str) and len(v) < 5 else "")
def test_malformed_model_files_get_one_line_and_write_nothing(tmp_path, suffix, text, message):
    path = tmp_path / ("bad." + suffix)
    path.write_text(text)
    out = tmp_path / "out"
    result = run("gen", path, "--target", "python", "-o", out)
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: %s\n" % (path, message)
    assert result.stdout == "" and not out.exists()


def test_lua_literal_reads_data_forms():
    table = parse_lua_table("return { 1, 'two', -3.5, 0x10, x = true, [\"y\"] = { nil_ok = false }; "
                            "'esc\\t\\65\\\\' } -- trailing comment")
    assert table == {1: 1, 2: "two", 3: -3.5, 4: 16, "x": True, "y": {"nil_ok": False}, 5: "esc\tA\\"}


def test_lua_literal_refuses_nesting_beyond_its_limit():
    with pytest.raises(LuaSyntaxError):
        parse_lua_table("{" * 40 + "}" * 40)
