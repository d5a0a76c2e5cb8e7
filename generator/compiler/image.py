"""Serialise :class:`~swarmvm.compiler.tables.Tables` as the portable table image (docs/image-format.md).

The image is the same bytes on every platform: little-endian, fixed widths given in its
header, sections in a fixed order, a CRC-16 at the end. Every runtime interprets it whether it
is compiled in or loaded at run time. Its header, section order and reader are defined once,
in the Python runtime's ``swarmvm_format`` (``FORMAT`` here); this module only encodes the
tables' sections."""

import hashlib
from collections.abc import Sequence
from typing import Optional

from ..boundary.errors import InputError
from . import runtime_files as runtime
from .tables import Tables

FORMAT = runtime.image_format()


def pack(tables: Tables, source: str, names: bool = True,
         order: Optional[tuple[Sequence[int], Sequence[int]]] = None,
         source_section: Optional[tuple[bytes, Sequence[int], Sequence[str]]] = None) -> bytes:
    """The image bytes; InputError when the model is too large for the format, or has no events
    (automata may declare none; the format needs one). ``order`` (each event's index in the
    source file, each global state's number in it) adds the order section; ``source_section``
    (the file's SHA-256, each supervisor's start state, each event's name as written, in
    canonical event order) the source section (docs/image-format.md)."""
    limits = [("events", tables.num_events, FORMAT.MAX_EVENTS),
              ("supervisors", tables.num_supervisors, FORMAT.MAX_SUPERVISORS),
              ("states", tables.num_states, FORMAT.MAX_STATES),
              ("transitions", tables.num_transitions, FORMAT.MAX_TRANSITIONS)]
    if tables.num_events == 0:
        raise InputError(source, "events", "no events: a supervisor set needs at least one")
    for what, count, limit in limits:
        if count > limit:
            raise InputError(source, "", "%d %s, over the image format's limit of %d" % (count, what, limit))
    m = tables.mask_bytes

    def mask(value: int) -> bytes:
        return value.to_bytes(m, "little")

    sections: dict[str, bytes] = {
        "controllable": mask(tables.controllable),
        "public": mask(tables.public),
        "supervisors": b"".join(mask(tables.sup_alphabet[s]) + FORMAT.SUPERVISOR_RECORD.pack(
            tables.sup_first_state[s], tables.sup_num_states[s], tables.sup_initial[s])
            for s in range(tables.num_supervisors)),
        "states": b"".join(mask(tables.state_defined[g]) + FORMAT.STATE_RECORD.pack(tables.state_first[g])
                           for g in range(tables.num_states)),
        "targets": b"".join(t.to_bytes(tables.state_width, "little") for t in tables.targets),
    }
    if tables.probs is not None:
        sections["probs"] = b"".join(FORMAT.PROB.pack(p) for p in tables.probs)
    if names:
        sections["names"] = b"".join(bytes([len(n)]) + n.encode("ascii") for n in tables.names)
    if order is not None:
        event_order, state_order = order
        sections["order"] = bytes(event_order) + b"".join(n.to_bytes(2, "little") for n in state_order)
    if source_section is not None:
        digest, start, written = source_section
        sections["source"] = (digest + b"".join(s.to_bytes(2, "little") for s in start)
                              + b"".join(bytes([len(n)]) + n.encode("ascii") for n in written))
    try:
        image: bytes = FORMAT.assemble(tables.num_events, tables.num_supervisors, tables.num_states,
                                       tables.num_transitions, tables.state_width, sections)
    except FORMAT.ImageError as exc:
        raise InputError(source, "", str(exc))
    return image


def digest(image: bytes) -> str:
    """Short content digest for banners: the first 16 hex digits of the image's SHA-256."""
    return hashlib.sha256(image).hexdigest()[:16]


def chunks(image: bytes) -> list[bytes]:
    """The image as stream chunks (runtime_c/swarmvm_stream.h): a sequence number, then the
    format's STREAM_CHUNK_DATA bytes of the image, the last chunk padded with zeros."""
    size: int = FORMAT.STREAM_CHUNK_DATA
    most: int = FORMAT.STREAM_MAX_CHUNKS
    count = (len(image) + size - 1) // size
    if count > most:
        raise ValueError("an image of %d bytes needs %d chunks; a stream carries at most %d" % (len(image), count, most))
    return [bytes([k]) + image[k * size:(k + 1) * size].ljust(size, b"\0") for k in range(count)]
