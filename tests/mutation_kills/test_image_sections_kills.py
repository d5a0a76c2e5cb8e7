"""The Python image reader (runtime_py/swarmvm_format.py) on images built section by section with
the format's own writer (`assemble`, so the checksum is right and only the checked part is odd):
what its second mutation run left unpinned (issue 29, docs/mutation.md) — masks of every width,
the probabilities' offset, the order and source sections at their bounds, the supervisor records'
refusal and the figures of the checksum message."""

import struct

import pytest

from swarmvm.readers.automaton import AutomatonBuilder
from swarmvm.boundary.errors import InputError
from one_state_image import one_state_image
from swarmvm.compiler.runtime_files import image_format

F = image_format()


def refusal(raw):
    with pytest.raises(F.ImageError) as refused:
        F.Image.parse(raw)
    return refused.value.code, str(refused.value)


@pytest.mark.parametrize("events", [1, 8, 9, 16, 17, 25, 32, 33, 40, 57, 64, 65, 72, 80])
def test_masks_of_every_width_are_read_bit_for_bit(events):
    """Widths 1, 2, 4 and 8 bytes unpack as integers, the others byte by byte: both on each side."""
    controllable = sum(1 << e for e in range(events) if e % 3 == 0) | 1 << (events - 1)
    parsed = F.Image.parse(one_state_image(events, controllable))
    assert (parsed.controllable, parsed.sup_alphabet, parsed.state_defined) == \
        (controllable, [(1 << events) - 1], [(1 << events) - 1])


def test_the_probabilities_are_read_behind_the_targets():
    parsed = F.Image.parse(one_state_image(3, 0b001, probs=[F.Q15_ONE, 1, 0x1234]))
    assert parsed.probs == [F.Q15_ONE, 1, 0x1234] and parsed.targets == [0, 0, 0]


def test_a_checksum_mismatch_names_both_values():
    raw = bytearray(one_state_image(3, 0b001))
    computed = F.crc16(bytes(raw[:-2]))
    raw[-2:] = b"\x34\xab"
    assert refusal(bytes(raw)) == (F.ErrorCode.CRC, "image checksum mismatch (stored 0xab34, computed 0x%04x)"
                                   % computed)


def names_and_order(events, order, state=0x0102):
    names = b"".join(bytes([1]) + bytes([ord("a") + e]) for e in range(events))
    return {"names": names, "order": bytes(order) + struct.pack("<H", state)}


def test_an_order_section_holds_each_event_index_below_the_event_count():
    parsed = F.Image.parse(one_state_image(3, 0b001, sections=names_and_order(3, [2, 0, 1])))
    assert (parsed.order, parsed.state_order) == ([2, 0, 1], [0x0102])
    assert refusal(one_state_image(3, 0b001, sections=names_and_order(3, [3, 0, 1]))) == \
        (F.ErrorCode.LAYOUT, "image order section names an event index beyond the 3 events")


def source(written, start=0x0203):
    return b"\x5a" * F.SOURCE_DIGEST_SIZE + struct.pack("<H", start) + b"".join(
        bytes([len(w)]) + w for w in written)


def test_a_source_section_gives_each_events_name_as_written():
    written = [b"EV_a", b"go-on", b"c" * 200]
    parsed = F.Image.parse(one_state_image(3, 0b001, sections={**names_and_order(3, [0, 1, 2]), "source": source(written)}))
    assert parsed.source == F.Source(b"\x5a" * 32, [0x0203], ["EV_a", "go-on", "c" * 200])


def test_a_source_section_shorter_than_its_digest_and_start_states_is_refused():
    raw = one_state_image(3, 0b001, sections={**names_and_order(3, [0, 1, 2]), "source": b"\x5a" * (F.SOURCE_DIGEST_SIZE + 1)})
    assert refusal(raw) == (F.ErrorCode.LAYOUT, "image source section runs past the checksum at byte %d"
                            % (len(raw) - F.CRC_SIZE))


def test_a_source_section_of_its_digest_and_start_states_alone_lacks_the_first_name():
    raw = one_state_image(3, 0b001, sections={**names_and_order(3, [0, 1, 2]), "source": source([])})
    assert refusal(raw) == (F.ErrorCode.LAYOUT, "image source section: event 0's written name runs past the "
                                                "checksum at byte %d" % (len(raw) - F.CRC_SIZE))


def test_a_source_name_longer_than_what_is_left_is_refused():
    """The last written name's length byte says one byte more than the section holds."""
    section = source([b"a", b"b", b"c"])
    raw = one_state_image(3, 0b001, sections={**names_and_order(3, [0, 1, 2]), "source": section[:-2] + b"\x02c"})
    end = len(raw) - F.CRC_SIZE
    assert refusal(raw) == (F.ErrorCode.LAYOUT, "image source section: event 2's written name runs past the "
                                                "checksum at byte %d" % end)


def two_supervisors(first, count, states=4):
    """Two supervisors over one event, the first of 2 states; the second's record is (first,
    count, initial 0); ``states`` in all."""
    record = F.SUPERVISOR_RECORD.pack
    sections = {"controllable": b"\x01", "public": b"\0",
                "supervisors": b"\x01" + record(0, 2, 0) + b"\x01" + record(first, count, 0),
                "states": (b"\0" + F.STATE_RECORD.pack(0)) * states, "targets": b""}
    return F.assemble(1, 2, states, 0, 1, sections)


@pytest.mark.parametrize("first,count,states,shown", [(2, 0, 4, "2..1"), (2, 0, 2, "2..1"), (3, 1, 4, "3..3"),
                                                      (2, 3, 4, "2..4")])
def test_a_supervisor_record_outside_its_place_is_refused_naming_its_states(first, count, states, shown):
    """A supervisor of no states is refused even where the state counts add up (2 + 0 of 2)."""
    assert refusal(two_supervisors(first, count, states)) == (
        F.ErrorCode.LAYOUT, "image supervisor 1: states %s (initial 0) do not follow the previous supervisor's "
                            "inside the %d states from its initial state 0" % (shown, states))
    assert F.Image.parse(two_supervisors(2, 2)).sup_num_states == [2, 2]


@pytest.mark.parametrize("supervisors,width", [(0, 1), (1, 3)])
def test_an_image_without_supervisors_or_with_odd_state_numbers_is_refused_by_its_header(supervisors, width):
    sections = {"controllable": b"\x01", "public": b"\0", "supervisors": b"", "states": b"", "targets": b""}
    assert refusal(F.assemble(3, supervisors, 0, 0, width, sections)) == (
        F.ErrorCode.LAYOUT, "image header inconsistent (events 3, mask bytes 1, state width %d, supervisors %d)"
        % (width, supervisors))


def test_an_image_of_the_format_maximum_is_not_refused_for_its_size():
    """65,535 bytes is within the format (then refused for its length field); one more is not."""
    raw = bytearray(one_state_image(3, 0b001))
    raw += bytes(F.MAX_IMAGE_SIZE - len(raw))
    assert refusal(bytes(raw)) == (F.ErrorCode.LENGTH, "image length field says %d bytes, got %d"
                                   % (len(one_state_image(3, 0b001)), F.MAX_IMAGE_SIZE))
    assert refusal(bytes(raw) + b"\0") == (F.ErrorCode.LENGTH, "image of %d bytes or more, over the format's "
                                            "maximum of %d" % (F.MAX_IMAGE_SIZE + 1, F.MAX_IMAGE_SIZE))


def test_assembling_an_image_over_the_format_maximum_is_refused_with_its_size():
    sections = {"controllable": b"\x01", "public": b"\0", "supervisors": b"", "states": b"",
                "targets": bytes(F.MAX_IMAGE_SIZE)}
    with pytest.raises(F.ImageError) as refused:
        F.assemble(3, 1, 1, 1, 1, sections)
    assert str(refused.value) == "table image would be %d bytes, over the format's limit of %d" % (
        F.HEADER_SIZE + F.MAX_IMAGE_SIZE + F.CRC_SIZE + 2, F.MAX_IMAGE_SIZE)


def test_the_transition_limit_is_the_largest_count_the_header_holds():
    fields = F.Header(F.MAGIC, F.FORMAT_VERSION, 0, 1, 1, 1, F.MAX_TRANSITIONS, 1, 1, F.MIN_IMAGE_SIZE)
    assert F.Header._make(F.HEADER.unpack(F.HEADER.pack(*fields))) == fields
    with pytest.raises(struct.error):
        F.HEADER.pack(*fields._replace(num_transitions=F.MAX_TRANSITIONS + 1))


@pytest.mark.parametrize("raw,message", [
    (one_state_image(defined=0b001, targets=[1]), "image transition 0 leads outside its supervisor 0"),
    (one_state_image(defined=0b001, targets=[0, 0], first_successor=1), "image state 0's successors start at target 1, not right after the "
                                                  "previous state's (0)"),
], ids=["target-outside-at-the-boundary", "successors-after-a-gap"])
def test_a_state_whose_successors_do_not_fit_the_target_section_is_refused(raw, message):
    assert refusal(raw) == (F.ErrorCode.LAYOUT, message)


def test_a_state_with_more_successors_than_the_header_counts_is_refused():
    """Three self-loops, the header counting two transitions (the target section sized for two)."""
    raw = one_state_image(defined=0b111, targets=[0, 0], transitions=2)
    assert refusal(raw) == (F.ErrorCode.LAYOUT, "image state 0 has successors outside the target section")


def test_a_file_is_read_to_one_byte_over_the_format_maximum(tmp_path):
    """An endless or huge file: the refusal names the bytes read, MAX_IMAGE_SIZE + 1."""
    path = tmp_path / "huge.svm"
    path.write_bytes(bytes(F.MAX_IMAGE_SIZE + 5))
    with pytest.raises(F.ImageError) as refused:
        F.Image.load(path)
    assert str(refused.value) == "image of %d bytes or more, over the format's maximum of %d" % (
        F.MAX_IMAGE_SIZE + 1, F.MAX_IMAGE_SIZE)


def test_the_smallest_image_is_a_header_and_its_checksum():
    """18 bytes pass the size check (then fail the length field); 17 do not."""
    assert refusal(bytes(F.MIN_IMAGE_SIZE)) == (F.ErrorCode.LENGTH, "image length field says 0 bytes, got %d"
                                                % F.MIN_IMAGE_SIZE)
    assert refusal(bytes(F.MIN_IMAGE_SIZE - 1)) == (F.ErrorCode.LENGTH, "image truncated: %d bytes, the header "
                                                    "alone needs %d" % (F.MIN_IMAGE_SIZE - 1, F.MIN_IMAGE_SIZE))


def test_a_wrong_magic_is_named_beside_the_expected_one():
    raw = b"XVMI" + one_state_image(3, 0b001)[4:]
    assert refusal(raw) == (F.ErrorCode.MAGIC, "not a swarmvm table image (magic b'XVMI', expected b'SVMI')")


def test_an_image_of_exactly_the_format_maximum_can_be_assembled():
    sections = {"controllable": b"\x01", "public": b"\0", "supervisors": b"", "states": b"",
                "targets": bytes(F.MAX_IMAGE_SIZE - F.HEADER_SIZE - F.CRC_SIZE - 2)}
    assert len(F.assemble(3, 1, 1, 1, 1, sections)) == F.MAX_IMAGE_SIZE


def test_a_source_section_without_an_order_section_is_refused():
    names = {"names": b"\x01a\x01b\x01c", "source": source([b"a", b"b", b"c"])}
    assert refusal(one_state_image(3, 0b001, sections=names)) == (
        F.ErrorCode.LAYOUT, "image has a source section without an order section: the compiler writes it only with one")


@pytest.mark.parametrize("names,message", [
    (b"\x01a\x01b", "image names section ends at event 2 of 3"),
    (b"\x01a\x01b\x02c", "image event 2's name runs past the checksum at byte %d"),
], ids=["a-name-missing", "one-byte-short"])
def test_a_names_section_short_of_its_last_name_is_refused(names, message):
    raw = one_state_image(3, 0b001, sections={"names": names})
    assert refusal(raw) == (F.ErrorCode.LAYOUT, message.replace("%d", str(len(raw) - F.CRC_SIZE)))


def test_a_name_of_255_characters_is_the_longest_a_length_byte_holds():
    """The reader reads one; the compiler accepts one and refuses a 256th character."""
    names = [b"a" * 255, b"b", b"c"]
    section = b"".join(bytes([len(n)]) + n for n in names)
    assert F.Image.parse(one_state_image(3, 0b001, sections={"names": section})).names == ["a" * 255, "b", "c"]
    builder = AutomatonBuilder("m.gen")
    builder.event(0, "a" * 255, True)
    with pytest.raises(InputError) as refused:
        builder.event(1, "b" * 256, True)
    assert str(refused.value).endswith("is not an event name (at most 255 letters, digits and '_')")
