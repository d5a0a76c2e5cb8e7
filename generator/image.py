"""Serialise :class:`~swarmvm.tables.Tables` as the portable table image (docs/image-format.md).

The image is the same bytes on every platform: little-endian, fixed widths given in its
header, sections in a fixed order, a CRC-16 at the end. Every runtime interprets it whether it
is compiled in or loaded at run time. The reader lives in the Python runtime
(``swarmvm_vm.Image``) so that parsing has one implementation; the generator reuses it."""

import hashlib
import struct

from . import runtime
from .errors import InputError

vm = runtime.python_vm()


def pack(tables, source, names=True):
    """The image bytes; InputError when the model is too large for the format."""
    limits = [("states", tables.num_states, 0xFFFF), ("transitions", tables.num_transitions, 0xFFFF)]
    for what, count, limit in limits:
        if count > limit:
            raise InputError(source, "", "%d %s, over the image format's limit of %d" % (count, what, limit))
    m = tables.mask_bytes

    def mask(value):
        return value.to_bytes(m, "little")

    body = bytearray()
    body += mask(tables.controllable) + mask(tables.public)
    for s in range(tables.num_supervisors):
        body += mask(tables.sup_alphabet[s])
        body += struct.pack("<HHH", tables.sup_first_state[s], tables.sup_num_states[s], tables.sup_initial[s])
    for g in range(tables.num_states):
        body += mask(tables.state_defined[g]) + struct.pack("<H", tables.state_first[g])
    for target in tables.targets:
        body += target.to_bytes(tables.state_width, "little")
    flags = 0
    if tables.probs is not None:
        flags |= vm.FLAG_PROBS
        body += struct.pack("<%dH" % len(tables.probs), *tables.probs)
    if names:
        flags |= vm.FLAG_NAMES
        for name in tables.names:
            encoded = name.encode("ascii")
            body += bytes([len(encoded)]) + encoded
    length = vm.HEADER_SIZE + len(body) + 2
    if length > 0xFFFF:
        raise InputError(source, "", "table image would be %d bytes, over the format's limit of 65535" % length)
    header = vm.MAGIC + struct.pack("<BBBBHHBBH", vm.FORMAT_VERSION, flags, tables.num_events,
                                    tables.num_supervisors, tables.num_states, tables.num_transitions,
                                    tables.state_width, m, length)
    image = bytes(header + body)
    return image + struct.pack("<H", vm.crc16(image))


def digest(image):
    """Short content digest for banners: the first 16 hex digits of the image's SHA-256."""
    return hashlib.sha256(image).hexdigest()[:16]


def chunks(image, size=8):
    """The image as stream chunks (runtime_c/swarmvm_stream.h): a sequence number, then
    ``size`` bytes of the image, the last chunk padded with zeros."""
    count = (len(image) + size - 1) // size
    if count > 256:
        raise ValueError("an image of %d bytes needs %d chunks; a stream carries at most 256" % (len(image), count))
    return [bytes([k]) + image[k * size:(k + 1) * size].ljust(size, b"\0") for k in range(count)]
