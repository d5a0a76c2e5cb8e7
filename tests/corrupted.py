"""A generated program's compiled-in image with one bit flipped, for the start-up refusal tests
of the C targets (host, Kilobot, CapBot)."""

import re


def corrupt_compiled_in_image(tables):
    """Flip one bit of a byte in the middle of the image array of a generated ``*_tables.c``
    (the build still compiles: only the checksum can tell)."""
    text = tables.read_text()
    start = text.index("_image[")
    values = [m for m in re.finditer(r"0x([0-9a-f]{2})", text) if m.start() > start]
    middle = values[len(values) // 2]
    flipped = "0x%02x" % (int(middle.group(1), 16) ^ 0x10)
    tables.write_text(text[:middle.start()] + flipped + text[middle.end():])
