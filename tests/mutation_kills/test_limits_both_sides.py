"""Limits pinned on both sides (issue 29): a limit tested on one side only let its off-by-one
mutant survive."""

import pytest

from swarmvm.compiler.image import chunks
from swarmvm.compiler.tables import q15, state_width


def test_256_states_number_in_one_byte_and_257_need_two():
    assert state_width(1) == 1 and state_width(256) == 1
    assert state_width(257) == 2 and state_width(65536) == 2
    assert state_width(65537) == 2       # over the format's limit: packing refuses it, not this


def test_an_image_one_byte_over_a_multiple_of_8_takes_one_more_chunk():
    eight, nine = bytes(range(8)), bytes(range(9))
    assert chunks(eight) == [b"\x00" + eight]
    assert chunks(nine) == [b"\x00" + eight, b"\x01\x08" + bytes(7)]
    assert len(chunks(bytes(8 * 256))) == 256
    with pytest.raises(ValueError, match="^an image of 2049 bytes needs 257 chunks; a stream carries at most 256$"):
        chunks(bytes(8 * 256 + 1))


def test_q15_rounds_half_up_and_stops_at_one():
    assert q15("1") == 32768 and q15("0") == 0
    assert q15(1 / 65536) == 1 and q15(0.99999) == 32768      # 0.5 and 32767.67 rounded up
