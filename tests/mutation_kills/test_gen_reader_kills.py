"""The libFAUDES .gen reader (generator/readers/faudes_gen.py) pinned where `make mutation` found it unpinned
(issue 29, docs/mutation.md): <Consecutive> ranges by known answers and on both sides of their
limit, the old style's generator name, empty sections, and the refusals' line numbers."""

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.readers.faudes_gen import read_gen


def read(tmp_path, text):
    path = tmp_path / "g.gen"
    path.write_text(text)
    return read_gen(str(path))


def refusal(tmp_path, text):
    with pytest.raises(InputError) as refused:
        read(tmp_path, text)
    return str(refused.value).removeprefix("%s: " % (tmp_path / "g.gen"))


def test_a_consecutive_range_names_each_state_from_first_to_last(tmp_path):
    """States 1, 2, 3 from <Consecutive> 1 3; 1 -a-> 3; 2 marked."""
    g = read(tmp_path, "<Generator> <Alphabet> a </Alphabet> <States> <Consecutive> 1 3 </Consecutive> </States>"
                       " <TransRel> 1 a 3 </TransRel> <InitStates> 1 </InitStates> <MarkedStates> 2 </MarkedStates>"
                       " </Generator>")
    assert len(g.supervisor.states) == 3 and g.supervisor.states[0][0].target == 2
    assert g.supervisor.marked == frozenset({1})


def test_a_consecutive_range_holds_at_most_65536_states(tmp_path):
    def states(last):
        return ("<Generator> <States> <Consecutive> 1 %d </Consecutive> </States> <InitStates> 1 </InitStates>"
                " </Generator>" % last)
    """One more than the format's MAX_STATES: a range that no image can hold."""
    assert len(read(tmp_path, states(65536)).supervisor.states) == 65536
    assert refusal(tmp_path, "\n" + states(65537)) == "States: line 2: <Consecutive> 1 65537: over 65536 states"


@pytest.mark.parametrize("range_", ["1 </Consecutive>", "a 3 </Consecutive>", "1 b </Consecutive>", "1"])
def test_a_consecutive_range_needs_two_numbers_and_its_end(tmp_path, range_):
    assert refusal(tmp_path, "<Generator> <States>\n<Consecutive> %s </States> </Generator>" % range_) \
        == "States: line 2: expected <Consecutive> first last </Consecutive>"


@pytest.mark.parametrize("alphabet", ["<Alphabet> </Alphabet>", "<Alphabet/>"])
def test_the_old_styles_generator_name_is_skipped_and_an_empty_section_read(tmp_path, alphabet):
    g = read(tmp_path, '<Generator> "G" %s <States> s </States> <InitStates> s </InitStates> </Generator>' % alphabet)
    assert g.events == {} and len(g.supervisor.states) == 1 and g.supervisor.initial == 0


def test_a_section_given_twice_is_refused_with_its_line(tmp_path):
    assert refusal(tmp_path, "<Generator> <Alphabet> a </Alphabet>\n<Alphabet> b </Alphabet> </Generator>") == \
        "Alphabet: line 2: section given twice"


@pytest.mark.parametrize("text,line", [('"x', 1), ('<Generator>\n<Alphabet> "a </Alphabet> </Generator>', 2)])
def test_an_unexpected_character_is_named_with_its_line(tmp_path, text, line):
    """An unclosed quote, at the very start of the file and on a later line."""
    assert refusal(tmp_path, text) == "line %d: unexpected character '\"'" % line


@pytest.mark.parametrize("text", ["<Generator/>", '<Generator name="G"/>', '<Generator name="G"/> </Generator>'])
def test_a_self_closed_generator_is_refused(tmp_path, text):
    assert refusal(tmp_path, text) == "Generator: expected <Generator> at the top"


def test_the_public_comment_makes_its_alphabet_events_public(tmp_path):
    g = read(tmp_path, "<Generator>\n% swarmvm public: a\n<Alphabet> a +C+ b </Alphabet> <States> s </States>"
                       " <InitStates> s </InitStates> </Generator>")
    assert g.events == {"a": (True, True), "b": (False, False)}


def test_a_generator_that_is_never_closed_is_refused(tmp_path):
    assert refusal(tmp_path, "<Generator>") == "Generator: missing </Generator>"


def test_a_state_attribute_is_ignored_in_states_and_refused_elsewhere(tmp_path):
    text = "<Generator> <States> s +o+ </States> <InitStates> s %s</InitStates> </Generator>"
    assert len(read(tmp_path, text % "").supervisor.states) == 1
    assert refusal(tmp_path, text % "+o+ ") == "InitStates: line 1: unexpected '+o+'"


def test_quoted_names_are_read_without_their_quotes_and_a_range_is_followed_by_more_states(tmp_path):
    """States 1, 2 from the range, then "s" (the initial state, the third)."""
    g = read(tmp_path, '<Generator> <Alphabet> "a" </Alphabet> <States> <Consecutive> 1 2 </Consecutive> "s" </States>'
                       ' <InitStates> s </InitStates> </Generator>')
    assert g.events == {"a": (False, False)} and len(g.supervisor.states) == 3 and g.supervisor.initial == 2


def test_a_tag_in_the_alphabet_is_refused_naming_it(tmp_path):
    assert refusal(tmp_path, "<Generator> <Alphabet> a <Consecutive> </Alphabet> </Generator>") == \
        "Alphabet: line 1: unexpected '<Consecutive>'"


def test_any_quoted_generator_name_is_skipped_and_a_transitions_attribute_ignored(tmp_path):
    """The old style's name is a string, even one spelled like a closing tag; +P+ after a triple
    is one of the attribute flags accepted and ignored."""
    g = read(tmp_path, '<Generator> "</Alphabet>" <Alphabet> a </Alphabet> <States> s </States>'
                       ' <TransRel> s a s +P+ </TransRel> <InitStates> s </InitStates> </Generator>')
    assert g.events == {"a": (False, False)} and [len(row) for row in g.supervisor.states] == [1]


@pytest.mark.parametrize("name", ["Alphabet", "States", "<Alphabet>"])
def test_a_quoted_generator_name_spelled_like_a_section_is_still_its_name(tmp_path, name):
    """A string is never a tag: the old style's name "Alphabet" or "<Alphabet>" is skipped."""
    g = read(tmp_path, '<Generator> "%s" <Alphabet> a </Alphabet> <States> s </States>'
                       ' <InitStates> s </InitStates> </Generator>' % name)
    assert g.events == {"a": (False, False)}


def unexpected(token):
    """The refusal of ``token`` where a section must start, on line 1."""
    return "Generator: line 1: unexpected %r (expected one of Alphabet, States, TransRel, InitStates, MarkedStates)" \
        % token


def test_a_quoted_tag_between_sections_is_refused_not_read_as_a_section(tmp_path):
    assert refusal(tmp_path, '<Generator> "G" "<Alphabet>" a </Alphabet> </Generator>') == unexpected("<Alphabet>")


def test_a_quoted_closing_tag_is_a_name_and_ends_nothing(tmp_path):
    """"</States>" is a state named so, "</Generator>" a stray string between sections."""
    g = read(tmp_path, '<Generator> <States> s "</States>" t </States> <InitStates> t </InitStates> </Generator>')
    assert len(g.supervisor.states) == 3 and g.supervisor.initial == 2
    assert refusal(tmp_path, '<Generator> <States> s </States> "</Generator>"') == unexpected("</Generator>")


def test_a_state_after_an_attribute_is_read(tmp_path):
    g = read(tmp_path, "<Generator> <States> s +o+ t </States> <InitStates> t </InitStates> </Generator>")
    assert len(g.supervisor.states) == 2 and g.supervisor.initial == 1


@pytest.mark.parametrize("tag", ["Generator", "Alphabet", "States", "TransRel", "InitStates", "MarkedStates",
                                 "Consecutive"])
def test_every_tag_spelled_in_a_string_is_a_state_name(tmp_path, tag):
    """The class of the two defects above: each tag of the format, opening, closing and
    self-closed, written as a quoted state name, is that name and ends or opens nothing."""
    names = ["<%s>" % tag, "</%s>" % tag, "<%s/>" % tag, tag]
    quoted = " ".join('"%s"' % name for name in names)
    g = read(tmp_path, '<Generator> "G" <States> %s s </States> <InitStates> s </InitStates> </Generator>' % quoted)
    assert len(g.supervisor.states) == len(names) + 1 and g.supervisor.initial == len(names)


def test_a_range_is_closed_by_the_tag_not_by_a_string_spelled_like_it(tmp_path):
    assert refusal(tmp_path, '<Generator> <States> <Consecutive> 1 2 "</Consecutive>" </States> </Generator>') == \
        "States: line 1: expected <Consecutive> first last </Consecutive>"
