"""swarmvm.boundary.escape, one function per output context (issue 23): each is read back, by the real
reader of its context, as the text it was given (C by gcc, Python by its parser, YAML by PyYAML,
CMake by cmake), or cannot leave its context (comments, terminal lines, Markdown cells)."""

import ast
import re
import subprocess

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from swarmvm.boundary import escape

# Arbitrary Unicode (no surrogates: they cannot be UTF-8), with the fragments that end contexts.
HOSTILE = st.lists(st.one_of(st.text(max_size=8), st.sampled_from(
    ["*/", "/*", "//", "\\", "\n", "\r", '"""', "'", '"', "??/", "--", "$(", "${x}", ";", "#", "|", "`", "\x1b[2J",
     "\u202e", "\0", "\x7f", "\U0001f600", "\\\n"])), max_size=6).map("".join)


@given(HOSTILE)
def test_a_comment_cannot_end_or_continue(text):
    out = escape.comment(text)
    assert out.isascii() and out.isprintable()
    for closer in ("*/", "/*", "--", "??", '"""', "\\\n"):
        assert closer not in out
    assert not out.endswith("\\")
    assert set(re.sub(r"\\(x[0-9a-f]{2}|u[0-9a-f]{4}|U[0-9a-f]{8}|[ntr])", "", out)) <= escape._COMMENT_SAFE


@given(HOSTILE)
def test_a_terminal_line_holds_no_control_character(text):
    out = escape.terminal(text)
    assert out.isprintable() and "\n" not in out and "\x1b" not in out


@given(HOSTILE)
def test_a_python_string_reads_back(text):
    literal = escape.py_string(text)
    assert literal.isascii() and literal.startswith('"')
    assert ast.literal_eval(literal) == text


@given(HOSTILE)
def test_a_yaml_string_reads_back(text):
    assert yaml.safe_load("key: " + escape.yaml_string(text)) == {"key": text}


@given(HOSTILE)
def test_a_markdown_cell_cannot_split(text):
    out = escape.markdown(text)
    assert "\n" not in out and re.search(r"(?<!\\)\|", out.replace("\\\\", "")) is None


@settings(max_examples=5, deadline=None)
@given(st.lists(HOSTILE, min_size=1, max_size=30))
def test_c_strings_read_back_through_gcc(tmp_path_factory, texts):
    """One C program printing every literal in hex: gcc reads each as the text's UTF-8 bytes."""
    folder = tmp_path_factory.mktemp("c_string")
    body = "\n".join('    dump(%s, sizeof %s - 1);' % (escape.c_string(t), escape.c_string(t)) for t in texts)
    (folder / "t.c").write_text('#include <stdio.h>\nstatic void dump(const char *s, unsigned long n) {\n'
                                '    while (n--) printf("%%02x", (unsigned char)*s++);\n    printf("\\n");\n}\n'
                                "int main(void) {\n%s\n    return 0;\n}\n" % body)
    subprocess.run(["gcc", "-std=c99", "-trigraphs", "-Wall", "-Werror", "-o", str(folder / "t"), str(folder / "t.c")],
                   check=True)
    out = subprocess.run([str(folder / "t")], capture_output=True, text=True, check=True).stdout.split("\n")
    assert out[:-1] == [t.encode("utf-8").hex() for t in texts]


@settings(max_examples=5, deadline=None)
@given(st.lists(HOSTILE.filter(lambda t: all(c.isprintable() or c in "\n\t\r" for c in t)), min_size=1, max_size=20))
def test_cmake_strings_read_back_through_cmake(tmp_path_factory, texts):
    folder = tmp_path_factory.mktemp("cmake_string")
    script = "".join('set(x %s)\nstring(HEX "${x}" h)\nmessage("${h}")\n' % escape.cmake_string(t) for t in texts)
    (folder / "t.cmake").write_text(script, encoding="utf-8")
    result = subprocess.run(["cmake", "-P", str(folder / "t.cmake")], capture_output=True, text=True, check=True)
    assert result.stderr.split("\n")[:-1] == [t.encode("utf-8").hex() for t in texts]


def test_cmake_refuses_a_control_character():
    with pytest.raises(escape.UnsafeText):
        escape.cmake_string("a\x1bb")


@pytest.mark.parametrize("bad", ["", "1x", "a-b", "a b", "é", "a\n", None, 3])
def test_an_identifier_is_validated_not_escaped(bad):
    with pytest.raises(escape.UnsafeText):
        escape.identifier(bad)


@settings(max_examples=40, deadline=None)
@given(text=st.lists(st.one_of(HOSTILE, st.sampled_from(["-Os", "-mcpu=cortex-m4", "--specs=rdimon.specs", "-Wl,--gc-sections",
                                                         "@m4.flags", "$(CC)", "a#b", "-DX='1'", "\\"])),
                         max_size=4).map(" ".join))
def test_make_words_are_read_back_by_make_and_the_shell_as_given(text, tmp_path_factory):
    """Words make_words lets through reach a recipe's command line unchanged (GNU make, then
    sh); anything else is refused: no reference, comment, quote or line break gets in."""
    try:
        words = escape.make_words(text)
    except escape.UnsafeText:
        assert not text.split() or any(not re.fullmatch(r"[A-Za-z0-9_+=,./:@-]+", w) for w in text.split())
        return
    makefile = tmp_path_factory.mktemp("make_words") / "Makefile"
    makefile.write_text("X = %s\nall:\n\t@printf '%%s\\n' $(X)\n" % words)
    out = subprocess.run(["make", "-s", "-f", str(makefile)], capture_output=True, text=True, check=True,
                         env={"PATH": "/usr/bin:/bin"})
    assert out.stdout.split("\n")[:-1] == text.split()


def test_make_words_take_the_capbot_compiler_flags():
    flags = "-mcpu=cortex-m4 -mthumb\n-std=c99 -Wall\n--specs=rdimon.specs -Wl,--gc-sections\n"
    assert escape.make_words(flags) == "-mcpu=cortex-m4 -mthumb -std=c99 -Wall --specs=rdimon.specs -Wl,--gc-sections"
    for bad in ("", "-DX=$(shell rm)", "a b#c", "-D'x'", None):
        with pytest.raises(escape.UnsafeText):
            escape.make_words(bad)


def test_identifier_parts_and_numbers():
    assert escape.identifier_part("1abc") == "1abc" and escape.identifier("EV_x") == "EV_x"
    assert escape.identifier_part("") == ""       # the event EV_ (tests/corpus/nadzoru2/flipflop_S.yaml)
    with pytest.raises(escape.UnsafeText):
        escape.identifier_part("a-b")
    assert escape.number(7, 3) == "7  "
    for bad in ("7", True, 7.0):
        with pytest.raises(escape.UnsafeText):
            escape.number(bad)


@pytest.mark.parametrize("bad", ["", 'a"b', "a b", "é", "a\nb"])
def test_a_gen_name_that_libfaudes_cannot_read_is_refused(bad):
    with pytest.raises(escape.UnsafeText):
        escape.gen_string(bad)


def test_dot_and_html():
    assert escape.dot_string('a"b\\n\nc') == '"a\\"b\\\\n\\\\nc"'
    assert escape.html('<a href="x">\x1b') == "&lt;a href=&quot;x&quot;&gt;\\x1b"
