"""The Lua table literal reader (generator/readers/lua_literal.py) pinned where `make mutation` found it
unpinned (issue 29, docs/mutation.md): its limits on both sides, decimal escapes at their ends,
the keys it refuses with the reason, and each refusal's message and line."""

import pytest

from swarmvm.readers.lua_literal import SHOWN, LuaSyntaxError, parse_lua_table


def refusal(text: str) -> str:
    with pytest.raises(LuaSyntaxError) as refused:
        parse_lua_table(text)
    return str(refused.value)


def nested(depth: int) -> str:
    return "{" * depth + "}" * depth


def test_tables_nest_32_deep_and_no_deeper():
    table = parse_lua_table(nested(32))
    for _ in range(31):
        (table,) = table.values()
    assert table == {}
    assert refusal(nested(33)) == "line 1: tables nested deeper than 32"


def test_a_number_has_at_most_64_characters_its_sign_not_counted():
    assert parse_lua_table("{ -%s }" % ("1" * 64)) == {1: -int("1" * 64)}
    assert refusal("{ %s }" % ("1" * 65)) == "line 1: a number of 65 characters (at most 64)"


@pytest.mark.parametrize("escape,char", [("\\0", "\0"), ("\\9", "\t"), ("\\255", "\xff"), ("\\0651", "A1")])
def test_a_decimal_escape_reads_up_to_three_digits_0_to_255(escape, char):
    assert parse_lua_table('{ "%s" }' % escape) == {1: char}


def test_a_decimal_escape_over_255_is_refused():
    assert refusal('{ "\\256" }') == "line 1: escape \\256 is out of range"


@pytest.mark.parametrize("key,what", [("nil", "nil"), ("{}", "a table"), ("true", "a boolean"), ("false", "a boolean")])
def test_a_key_that_is_not_a_string_or_a_number_is_refused_saying_what_it_is(key, what):
    assert refusal("{\n [%s] = 1 }" % key) == "line 2: a key must be a string or a number, not %s" % what


def test_only_a_name_is_a_key_before_an_equals_sign():
    """`1 = 2` is a positional 1 followed by a stray `=`; `true = 1` likewise."""
    assert refusal("{ 1 = 2 }") == "line 1: expected ',' or '}', found '='"
    assert refusal("{ true = 1 }") == "line 1: expected ',' or '}', found '='"
    assert parse_lua_table("{ a = 1, 2 }") == {"a": 1, 1: 2}


def test_an_expected_token_is_named_with_what_was_found():
    assert refusal("{ [1] 2 }") == "line 1: expected '=', found '2'"
    assert refusal("{ [1") == "line 1: expected ']', found end of file"


def test_a_long_token_is_shown_cut_to_40_characters():
    long_key = "k" * 100
    shown = repr(long_key)[:37] + "..."
    assert len(shown) == SHOWN
    assert refusal('{ ["%s"] = 1, ["%s"] = 2 }' % (long_key, long_key)) == "line 1: key %s given twice" % shown
    assert refusal("{ x = 1 %s }" % long_key) == "line 1: expected ',' or '}', found %s" % shown


def test_text_after_the_table_is_refused_with_its_line():
    assert refusal("{}\n\n  x") == "line 3: unexpected 'x' after the table"


def test_an_unknown_escape_is_named():
    assert refusal('{ "a\\qb" }') == "line 1: unknown escape \\q in a string"


@pytest.mark.parametrize("text", ["", "  -- only a comment\n"])
def test_a_file_without_a_table_is_refused_at_its_end(text):
    assert refusal(text) == "line %d: expected a table constructor '{', found end of file" % (1 + text.count("\n"))


def test_two_values_without_a_separator_are_refused():
    """A number after a value is not negated: only `-` before a number is."""
    assert refusal("{ 5 6 }") == "line 1: expected ',' or '}', found '6'"
    assert parse_lua_table("{ 5, -6 }") == {1: 5, 2: -6}


def test_a_token_of_40_characters_is_shown_whole():
    key = "k" * 38                                  # repr: 40 characters with its quotes
    assert refusal('{ ["%s"] = 1, ["%s"] = 2 }' % (key, key)) == "line 1: key %r given twice" % key
