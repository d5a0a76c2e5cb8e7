"""The Python image reader (runtime_py/swarmvm_format.py) on images written for one check each:
mutants of the name-by-name walk, of the header's event count and of the event-mask checks survived
the other image tests (issue 29, docs/mutation.md)."""

import pytest

from one_state_image import one_state_image
from swarmvm.compiler.runtime_files import image_format

FORMAT = image_format()


def image(events=3, controllable=0b001, alphabet=0b111, defined=0, names=None):
    """One supervisor of one state, ``defined`` its events (self-loops), ``names`` its names section."""
    sections = None if names is None else {"names": b"".join(bytes([len(n)]) + n.encode() for n in names)}
    return one_state_image(events, controllable, alphabet, defined, sections=sections)


def refusal(raw):
    with pytest.raises(FORMAT.ImageError) as refused:
        FORMAT.Image.parse(raw)
    assert refused.value.code == FORMAT.ErrorCode.LAYOUT
    return str(refused.value)


def test_names_whose_length_byte_is_a_name_character_are_walked_one_by_one():
    """A name of 48 characters has the length byte '0': the section cannot be split at the bytes
    that are no name characters, and is read name by name."""
    names = ["a" * 48, "b", "c" * 57]
    assert FORMAT.Image.parse(image(names=names)).names == names
    assert FORMAT.Image.parse(image(names=["a" * 47, "b", "c"])).names == ["a" * 47, "b", "c"]


def test_an_image_of_one_event_is_read_and_of_none_refused():
    assert FORMAT.Image.parse(image(events=1, controllable=1, alphabet=1, defined=1)).num_events == 1
    assert refusal(image(events=0, controllable=0, alphabet=0)) == (
        "image header inconsistent (events 0, mask bytes 0, state width 1, supervisors 1)")


@pytest.mark.parametrize("raw,message", [
    (image(controllable=0b1000), "image event masks name events beyond the 3 events"),
    (image(alphabet=0b1111), "image supervisor 0's alphabet names events beyond the 3 events"),
    (image(alphabet=0b1111, defined=0b1000), "image supervisor 0's alphabet names events beyond the 3 events"),
    (image(alphabet=0b011, defined=0b100), "image state 0 has transitions on events outside its supervisor 0's "
                                           "alphabet"),
], ids=["controllable", "alphabet", "alphabet-and-state", "state-outside-alphabet"])
def test_masks_beyond_the_events_or_the_alphabet_are_refused(raw, message):
    assert refusal(raw) == message


def test_masks_inside_the_events_are_read():
    parsed = FORMAT.Image.parse(image(controllable=0b101, alphabet=0b111, defined=0b110))
    assert (parsed.controllable, parsed.sup_alphabet, parsed.state_defined, parsed.targets) == (0b101, [7], [6], [0, 0])


def test_an_event_is_found_by_its_name_with_or_without_ev():
    parsed = FORMAT.Image.parse(image(names=["go", "hit", "stop"]))
    assert parsed.event_index("EV_hit") == parsed.event_index("hit") == 1
    assert parsed.event_name(2) == "EV_stop"
    with pytest.raises(KeyError, match="no event named 'EV_run'"):
        parsed.event_index("EV_run")
