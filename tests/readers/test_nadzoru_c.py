"""Nadzoru's generated C as an input (issue 35, point 3): `check`, `gen`, `pack` and everything
that reads a supervisor take a C source or header holding the published tables, so a team whose
supervisor.yaml is lost starts from its program; a file of no known kind is refused in one line
naming the kinds swarmvm reads."""

import subprocess
from pathlib import Path

import pytest

import nadzoru_c_form
from swarmvm import api
from swarmvm.boundary.errors import InputError
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.readers import READERS, SUPERVISOR_READERS, read_supervisor
from swarmvm.readers.nadzoru_c import read_nadzoru_c

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus"
FREEBOT = ROOT.parent / "shared" / "reference" / "freebot-capbot-sct"
# Every corpus supervisor but the probabilistic one (Nadzoru's C VM has no probabilities).
YAMLS = sorted(p for p in CORPUS.glob("*/*.yaml") if "sup_data_prob" not in p.read_text())


def _same_supervisor(a, b) -> None:
    """Two reads give the same supervisor set: the same canonical tables and image body."""
    first, second = compile_inputs([str(a)]), compile_inputs([str(b)])
    assert first.model.events == second.model.events
    assert first.tables == second.tables
    assert first.packed_image != b"" and second.packed_image != b""


@pytest.mark.parametrize("layout", ["header", "inline"])
@pytest.mark.parametrize("path", YAMLS, ids=lambda p: p.stem)
def test_the_c_form_of_every_corpus_supervisor_reads_as_its_yaml(path, layout, tmp_path):
    source = nadzoru_c_form.write(path, tmp_path, layout)
    _same_supervisor(source, path)
    c, y = read_nadzoru_c(str(source)), read_supervisor(str(path))
    assert (c.events, c.controllable, c.public, c.written, c.current) == (y.events, y.controllable, y.public,
                                                                          y.written, y.current)
    assert c.supervisors == y.supervisors


@pytest.mark.skipif(not FREEBOT.is_dir(), reason="needs ../shared/reference beside the checkout")
def test_the_published_capbot_tables_read_as_the_corpus_yaml_rebuilt_from_them():
    """FreeBot's generic_mic.c is the source of the corpus' capbot_demo.yaml."""
    _same_supervisor(FREEBOT / "lib/sct/src/generic_mic.c", CORPUS / "openswarm" / "capbot_demo.yaml")


@pytest.mark.skipif(not FREEBOT.is_dir(), reason="needs ../shared/reference beside the checkout")
def test_check_gen_and_pack_take_the_published_capbot_program(tmp_path):
    """The work_and_charge tables, their EV_ defines in ../inc/ as the published layout has them."""
    source = str(FREEBOT / "lib/sct/src/sct_work_and_charge.c")
    check = subprocess.run(["swarmvm", "check", source], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    assert "| %s | 8 | 4 | 32 | 156 |" % source in check.stdout
    gen = subprocess.run(["swarmvm", "gen", source, "--target", "c", "-o", str(tmp_path / "c")],
                         capture_output=True, text=True)
    assert gen.returncode == 0, gen.stderr
    assert (tmp_path / "c" / "sct_work_and_charge_tables.c").is_file()
    pack = subprocess.run(["swarmvm", "pack", source, "-o", str(tmp_path / "w.svm")], capture_output=True, text=True)
    assert pack.returncode == 0, pack.stderr
    assert api.read_image(str(tmp_path / "w.svm")).num_events == 8


def test_the_c_file_keeps_the_files_event_order_for_exact_mode(tmp_path):
    """As from a supervisor.yaml, pack records the file's event order and current states."""
    yaml_path = CORPUS / "openswarm" / "energy_worker.yaml"
    source = nadzoru_c_form.write(yaml_path, tmp_path, "inline")
    assert compile_inputs([str(source)]).ordered_image != compile_inputs([str(source)]).image


def _refused(path: Path) -> str:
    with pytest.raises(InputError) as caught:
        read_supervisor(str(path))
    line = str(caught.value)
    assert "\n" not in line and line.startswith(str(path) + ":")
    return line


def _inline(tmp_path: Path, edit) -> Path:
    source = nadzoru_c_form.write(CORPUS / "openswarm" / "capbot_demo.yaml", tmp_path, "inline")
    source.write_text(edit(source.read_text()))
    return source


@pytest.mark.parametrize("edit, key, words", [
    (lambda t: t.replace("#define EV_stop 2", "#define EV_stop 7"), "events", "numbered from 0"),
    (lambda t: t.replace("#define EV_stop 2", "#define EV_stop 1"), "EV_stop", "has the value 1 of EV_btnStop"),
    (lambda t: t.replace("EV_btnMove,0,2 }", "EV_nowhere,0,2 }"), "sup_data[31]", "EV_nowhere is not defined"),
    (lambda t: t.replace("EV_btnMove,0,2 };", "EV_btnMove,0,2 "), "sup_data", "expected ',' or '}'"),
    (lambda t: t.replace("{ 1,0,1,0 }", "{ 1,0,1,0x }"), "ev_controllable[3]", "not an integer literal"),
    (lambda t: t.replace("{ 1,0,1,0 }", "{ 1,0,1,%s }" % ("9" * 5000)), "ev_controllable[3]", "at most 20 characters"),
    (lambda t: t.replace("#define EV_stop 2", "#define EV_stop %s" % ("9" * 5000)), "EV_stop",
     "value of over 20 characters"),
    (lambda t: t.replace("{ 1,0,1,0 }", "{ 1,0,1,{{{{{0}}}}} }"), "ev_controllable", "nested more than"),
    (lambda t: t.replace("{ 1,0,1,0 }", "{ 1,0,1,2 }"), "ev_controllable[3]", "not 0 or 1"),
    (lambda t: t + "const unsigned char sup_data[1] = { 0 };\n", "sup_data", "defined twice"),
    (lambda t: t.replace("sup_data_pos[1] = { 0 };", ""), "sup_data_pos", "table not defined here"),
], ids=["gap", "duplicate_value", "undefined_name", "unterminated", "bad_literal", "huge_literal", "huge_define",
        "too_deep", "yaml_check",
        "twice", "missing_table"])
def test_a_bad_table_is_one_line_naming_file_table_and_line(tmp_path, edit, key, words):
    line = _refused(_inline(tmp_path, edit))
    assert ": %s:" % key in line and words in line, line


def test_a_missing_header_is_named(tmp_path):
    source = nadzoru_c_form.write(CORPUS / "openswarm" / "capbot_demo.yaml", tmp_path, "header")
    (tmp_path / "lib/sct/inc/sct_model.h").unlink()
    line = _refused(source)
    assert 'not found: "sct_model.h"' in line, line


def test_comments_and_the_rest_of_a_program_are_ignored(tmp_path):
    source = _inline(tmp_path, lambda t: t.replace("/* tables */", "/* const unsigned char sup_data[2] = {1,2}; */\n"
                                                   "// #define EV_stop 9\nchar *s = \"/* not a comment\";\n"))
    _same_supervisor(source, CORPUS / "openswarm" / "capbot_demo.yaml")


@pytest.mark.parametrize("name, text", [("tables.h", "#define EV_a 0\nvoid SCT_init();\n"),
                                        ("main.c", "int main(void) { return 0; }\n")])
def test_a_c_file_without_tables_says_so(tmp_path, name, text):
    (tmp_path / name).write_text(text)
    assert "not a Nadzoru C supervisor: it defines none of its tables" in _refused(tmp_path / name)


@pytest.mark.parametrize("name", ["notes.txt", "supervisor", "model.json"])
def test_a_file_of_no_known_kind_names_the_kinds_swarmvm_reads(tmp_path, name):
    (tmp_path / name).write_text("num_events: 1\n")
    result = subprocess.run(["swarmvm", "check", str(tmp_path / name)], capture_output=True, text=True)
    assert result.returncode == 2 and result.stdout == ""
    assert "not a file swarmvm reads" in result.stderr
    for suffix in (*SUPERVISOR_READERS, *READERS):
        assert suffix in result.stderr
