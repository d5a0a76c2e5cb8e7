"""Every reader ends bad input in one line (issue 23, class 3): generated inputs, not examples.

Two generative properties (hypothesis):

- the Lua literal reader (swarmvm.readers.lua_literal) and the ``.nza`` reader, given arbitrary text and
  structured random Lua-like literals (nested tables, keys of every kind, long numbers, strings
  with escapes, huge exponents, deep nesting), either load or refuse: LuaSyntaxError from the
  literal reader, one printable InputError line from the ``.nza`` reader; nothing else;
- every reader of tests/fuzz/readers.py (supervisor YAML, Nadzoru 2 XML, ``.xmd``, ``.nza``,
  ``.gen``, the ``.svm`` readers, event scripts), given the corpus's files mutated (bytes flipped,
  the file cut, bytes inserted, lines duplicated or dropped), loads or refuses with its own error
  (InputError; the runtime's ImageError, which must also agree with the C reader).

``make test`` draws 200 examples per property (the ``ci`` profile of tests/conftest.py: the same
ones every run); ``make fuzz`` (HYPOTHESIS_PROFILE=long) 5,000, at random (docs/fuzzing.md)."""

import os

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz import readers
from swarmvm.readers.lua_literal import LuaSyntaxError, parse_lua_table

# The profile's settings (derandomized or not, no deadline), with more examples than its default:
# a reader refuses most inputs in well under a millisecond.
SETTINGS = settings(max_examples=5000 if os.environ.get("HYPOTHESIS_PROFILE") == "long" else 200)


@pytest.fixture(scope="module", autouse=True)
def _input_files():
    """The readers write their inputs into a folder of this process: removed afterwards."""
    yield
    readers.cleanup()


# ---- Lua-like literals ---------------------------------------------------------------------------

ESCAPES = ["\\n", "\\t", "\\\\", "\\\"", "\\'", "\\0", "\\255", "\\256", "\\999", "\\x41", "\\u{41}", "\\z", "\\q",
           "\\\n", "\\"]
NUMBERS = st.one_of(
    st.integers(-10 ** 30, 10 ** 30).map(str),
    st.integers(1, 6000).map(lambda n: "9" * n),                         # thousands of digits
    st.integers(1, 200).map(lambda n: "0x" + "f" * n),
    st.tuples(st.integers(0, 10 ** 6), st.integers(-10 ** 9, 10 ** 9)).map(lambda p: "%de%d" % p),   # huge exponents
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.sampled_from([".5", "5.", "1e", "0x", "1e+", "--1", "- 1", "1.2.3", "0X1p4", "inf", "nan", "-0"]),
)
STRINGS = st.lists(st.one_of(st.text(max_size=8), st.sampled_from(ESCAPES)), max_size=6).flatmap(
    lambda parts: st.sampled_from(['"%s"', "'%s'", "[[%s]]"]).map(lambda quote: quote % "".join(parts)))
NAMES = st.one_of(st.sampled_from(["states", "events", "transitions", "name", "initial", "marked", "controllable",
                                   "shared", "source", "target", "event", "x", "true", "nil", "return", "and"]),
                  st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,6}", fullmatch=True))
SCALARS = st.one_of(NUMBERS, STRINGS, st.sampled_from(["true", "false", "nil"]))


def _table(values):
    """A table constructor over ``values``: positional, ``name =`` and ``[key] =`` entries,
    any value (a table too) as a key, with ',' or ';' between and perhaps after."""
    entry = st.one_of(values, st.tuples(NAMES, values).map(lambda kv: "%s = %s" % kv),
                      st.tuples(values, values).map(lambda kv: "[%s] = %s" % kv))
    return st.tuples(st.lists(entry, max_size=5), st.sampled_from([",", ";", " ,", ""]), st.booleans()).map(
        lambda t: "{" + (t[1] or ",").join(t[0]) + (t[1] if t[2] else "") + "}")


LITERALS = st.recursive(SCALARS, _table, max_leaves=30)
NESTING = st.integers(1, 200).map(lambda n: "{" * n + "}" * n)
LUA_TEXT = st.one_of(
    LITERALS.map(lambda t: "return " + t), _table(LITERALS), NESTING, st.text(max_size=200),
    st.text(alphabet="{}[]=,;-'\"\\0123456789.eExX+ \nabc_", max_size=200))


def _nza_document(parts):
    """A ``.nza``-shaped document: its three lists given random (or random-entried) values."""
    return "return { states = %s, events = %s, transitions = %s }" % parts


def _entries(fields):
    """A Lua list of tables whose fields are those an .nza entry has, with random values."""
    entry = st.lists(st.tuples(st.sampled_from(fields), LITERALS), max_size=4).map(
        lambda kvs: "{" + ", ".join("%s = %s" % kv for kv in kvs) + "}")
    return st.lists(st.one_of(entry, LITERALS), max_size=4).map(lambda items: "{" + ", ".join(items) + "}")


NZA_TEXT = st.one_of(
    LUA_TEXT,
    st.tuples(_entries(["initial", "marked", "x", "y"]), _entries(["name", "controllable", "shared"]),
              _entries(["source", "target", "event"])).map(_nza_document))


@SETTINGS
@given(LUA_TEXT)
def test_the_lua_literal_reader_loads_or_refuses(text):
    try:
        table = parse_lua_table(text)
    except LuaSyntaxError as exc:
        assert "\n" not in exc.message
        return
    assert isinstance(table, dict)


@SETTINGS
@given(NZA_TEXT)
def test_the_nza_reader_loads_or_refuses_in_one_line(text):
    readers.READERS["nza"](text.encode("utf-8", "surrogatepass"))


@pytest.mark.parametrize("text, message", [
    ("return {x = " + "9" * 5000 + "}", "a number of 5000 characters"),
    ("return {[{}] = 1}", "a key must be a string or a number, not a table"),
    ("return {[true] = 1, [1] = 2}", "not a boolean"),
    ("return {[1] = 1, [1.0] = 2}", "key 1.0 given twice"),
    ("return {x = 1, x = 2}", "key 'x' given twice"),
    ('return {x = 1 "' + "a" * 1000 + '"}', "expected ',' or '}', found '\"aaa"),
])
def test_what_a_dict_cannot_hold_is_refused(text, message):
    with pytest.raises(LuaSyntaxError, match=message) as refused:
        parse_lua_table(text)
    assert len(refused.value.message) < 100


# ---- mutations of the corpus ---------------------------------------------------------------------

def _mutate(data: bytes, edits) -> bytes:
    """``data`` after each edit: ("flip", at, bit), ("cut", at), ("insert", at, bytes),
    ("duplicate", line), ("drop", line); positions are taken modulo the size."""
    out = bytearray(data)
    for kind, at, extra in edits:
        if kind == "flip" and out:
            out[at % len(out)] ^= 1 << (extra[0] % 8 if extra else 0)
        elif kind == "cut":
            del out[at % (len(out) + 1):]
        elif kind == "insert":
            out[at % (len(out) + 1):at % (len(out) + 1)] = extra
        else:
            lines = bytes(out).splitlines(keepends=True)
            if lines:
                k = at % len(lines)
                lines[k:k + 1] = [lines[k]] * (2 if kind == "duplicate" else 0)
                out = bytearray(b"".join(lines))
    return bytes(out)


EDITS = st.lists(st.tuples(st.sampled_from(["flip", "cut", "insert", "duplicate", "drop"]), st.integers(0, 1 << 16),
                           st.binary(max_size=8)), min_size=1, max_size=4)


@pytest.mark.parametrize("reader", sorted(readers.READERS))
def test_every_reader_loads_or_refuses_mutated_corpus_files(reader):
    seeds = sorted(readers.seeds(reader).values())

    @SETTINGS
    @given(st.sampled_from(seeds), EDITS)
    def holds(seed, edits):
        readers.READERS[reader](_mutate(seed, edits))

    holds()
