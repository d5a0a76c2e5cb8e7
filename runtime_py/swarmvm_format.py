"""The swarmvm table image format, defined once: docs/image-format.md in code.

Magic, version, header fields and their offsets, flags, section order, limits, the codes a
reader gives a refused image, the checksum, the writer's assembly and the reader. The generator
(generator/image.py) writes images with :func:`assemble`; the Python VM (swarmvm_vm.py) reads
them with :meth:`Image.parse`. The C and C++ runtimes keep their own constants (a
microcontroller cannot import this file); tests/image/test_format_constants.py checks them
against these, and tests/image/test_reader_parity.py checks that all three readers give the
same code for the same bad image. Standard library only: it ships beside swarmvm_vm.py, onto a
robot too.
"""

import binascii
import enum
import itertools
import operator
import struct
from typing import Dict, List, NamedTuple, Optional

__all__ = ["ErrorCode", "Header", "Image", "ImageError", "assemble", "crc16", "read_header"]

MAGIC = b"SVMI"
FORMAT_VERSION = 1


class Header(NamedTuple):
    """The header's fields, in image order (docs/image-format.md's table)."""

    magic: bytes
    version: int
    flags: int
    num_events: int
    num_supervisors: int
    num_states: int
    num_transitions: int
    state_width: int
    mask_bytes: int
    length: int

    @classmethod
    def unpack(cls, raw: bytes) -> "Header":
        """The fields of the first HEADER_SIZE bytes of ``raw``, unchecked."""
        return cls._make(HEADER.unpack_from(raw))


# Each field's struct code (little-endian); every offset follows from them.
HEADER_FIELDS = tuple(zip(Header._fields, ("4s", "B", "B", "B", "B", "H", "H", "B", "B", "H")))
HEADER = struct.Struct("<" + "".join(code for _, code in HEADER_FIELDS))
HEADER_SIZE = HEADER.size
OFFSETS = {name: struct.calcsize("<" + "".join(code for _, code in HEADER_FIELDS[:i]))
           for i, (name, _) in enumerate(HEADER_FIELDS)}
CRC_SIZE = 2
MIN_IMAGE_SIZE = HEADER_SIZE + CRC_SIZE
MAX_IMAGE_SIZE = 0xFFFF             # L is a u16

FLAG_NAMES = 0x01                   # the names section is present
FLAG_PROBS = 0x02                   # the probability section is present
FLAG_ORDER = 0x04                   # the order section is present
KNOWN_FLAGS = FLAG_NAMES | FLAG_PROBS | FLAG_ORDER   # any other bit set: refused (ErrorCode.LAYOUT)

MAX_EVENTS = 0xFF
MAX_SUPERVISORS = 0xFF
MAX_STATES = 0xFFFF
MAX_TRANSITIONS = 0xFFFF
STATE_WIDTHS = (1, 2)               # bytes of a target state number

# Sections in image order; "probs", "names" and "order" only with their flag. "order" holds, for
# each event (canonical index), its index in the source file's event list (one byte, below the
# event count), then for each state (global index) its number in the source file (u16): what the
# compatibility API's exact mode steps and reports by (docs/compat.md).
SECTIONS = ("controllable", "public", "supervisors", "states", "targets", "probs", "names", "order")
SUPERVISOR_RECORD = struct.Struct("<HHH")   # after the alphabet mask: first state, state count, initial state
STATE_RECORD = struct.Struct("<H")          # after the defined mask: index of the first successor
PROB = struct.Struct("<H")                  # Q15
Q15_ONE = 32768

# Bytes an event name may hold (the input languages' rule: letters, digits and '_').
NAME_CHARS = frozenset(b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ_abcdefghijklmnopqrstuvwxyz")
MAX_NAME_LENGTH = 0xFF


class ErrorCode(enum.IntEnum):
    """Result codes, numbered as swarmvm.h's ``svm_result`` (SVM_OK, SVM_ERR_<NAME>).

    A reader refuses an image with the first of LENGTH .. LAYOUT that applies, in this order;
    LIMITS is a C build's compile-time maxima; the others come from C API calls, not images."""

    OK = 0
    LENGTH = 1          # shorter than MIN_IMAGE_SIZE, longer than MAX_IMAGE_SIZE, or L != the length
    MAGIC = 2           # not MAGIC
    VERSION = 3         # a format version this reader does not read
    CRC = 4             # checksum mismatch
    LAYOUT = 5          # header inconsistent, sections do not end at L-2, an index or name out of range
    LIMITS = 6          # more events/supervisors/states than the build's SVM_MAX_*
    NAMES = 7           # swap: a bound event's name is missing from the new image
    EVENT = 8           # unknown event index, or a check bound to a controllable event
    NO_BINDINGS = 9     # svm_bind without a binding table
    SOURCE = 10         # an image in memory this build does not read


class ImageError(ValueError):
    """A table image that cannot be run; ``code`` (:class:`ErrorCode`) says why, as C does."""

    def __init__(self, code: ErrorCode, message: str) -> None:
        super().__init__(message)
        self.code = code


# Each byte value with its bits in reverse order.
_REVERSED = bytes(sum(1 << (7 - bit) for bit in range(8) if value >> bit & 1) for value in range(256))


def _reverse16(value: int) -> int:
    return _REVERSED[value & 0xFF] << 8 | _REVERSED[value >> 8]


def crc16(data: bytes, crc: int = 0xFFFF) -> int:
    """CRC-16 with the reflected CCITT polynomial 0x8408, no final xor (CRC-16/MCRF4XX).

    It is what avr-libc's ``_crc_ccitt_update`` computes, so the Kilobot checks an image
    with the library routine it already has. Computed by the standard library's table-driven
    CRC-CCITT in C (``binascii.crc_hqx``, the same polynomial unreflected): a reflected CRC is
    the unreflected one of the bit-reversed bytes, bit-reversed; a Python loop over the bytes
    was most of an image's load time."""
    return _reverse16(binascii.crc_hqx(bytes(data).translate(_REVERSED), _reverse16(crc)))


def assemble(num_events: int, num_supervisors: int, num_states: int, num_transitions: int, state_width: int,
             sections: Dict[str, bytes]) -> bytes:
    """The image: header, ``sections`` ({name: bytes}) in SECTIONS order, CRC.

    "probs", "names" and "order" are optional and set their flags. :class:`ImageError` (LENGTH) when the
    image would exceed MAX_IMAGE_SIZE."""
    body = b"".join(sections[name] for name in SECTIONS if name in sections)
    length = HEADER_SIZE + len(body) + CRC_SIZE
    if length > MAX_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "table image would be %d bytes, over the format's limit of %d"
                         % (length, MAX_IMAGE_SIZE))
    flags = ((FLAG_PROBS if "probs" in sections else 0) | (FLAG_NAMES if "names" in sections else 0)
             | (FLAG_ORDER if "order" in sections else 0))
    mask_bytes = (num_events + 7) // 8
    image = HEADER.pack(*Header(MAGIC, FORMAT_VERSION, flags, num_events, num_supervisors, num_states,
                                num_transitions, state_width, mask_bytes, length)) + body
    return image + struct.pack("<H", crc16(image))


def read_header(raw: bytes) -> Header:
    """The header of ``raw`` once the checks before the layout passed (length, magic, version,
    CRC, in that order); :class:`ImageError` with the first that fails."""
    size = len(raw)
    if size < MIN_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "image truncated: %d bytes, the header alone needs %d" % (size, MIN_IMAGE_SIZE))
    if size > MAX_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "image of %d bytes or more, over the format's maximum of %d"
                         % (size, MAX_IMAGE_SIZE))
    header = Header.unpack(raw)
    if header.length != size:
        raise ImageError(ErrorCode.LENGTH, "image length field says %d bytes, got %d" % (header.length, size))
    if header.magic != MAGIC:
        raise ImageError(ErrorCode.MAGIC, "not a swarmvm table image (magic %r, expected %r)" % (header.magic, MAGIC))
    if header.version != FORMAT_VERSION:
        raise ImageError(ErrorCode.VERSION, "image format version %d, this VM reads version %d"
                         % (header.version, FORMAT_VERSION))
    end = size - CRC_SIZE
    stored, computed = _u16(raw, end), crc16(raw[:end])
    if stored != computed:
        raise ImageError(ErrorCode.CRC, "image checksum mismatch (stored 0x%04x, computed 0x%04x)" % (stored, computed))
    return header


def _layout_error(message: str) -> ImageError:
    return ImageError(ErrorCode.LAYOUT, message)


def _u16(raw: bytes, pos: int) -> int:
    return raw[pos] | (raw[pos + 1] << 8)


def _numbers(raw: bytes, pos: int, count: int, width: int) -> List[int]:
    """``count`` little-endian unsigned numbers of ``width`` (1 or 2) bytes at ``pos``."""
    chunk = raw[pos:pos + count * width]
    return list(chunk) if width == 1 else list(struct.unpack("<%dH" % count, chunk))


def _records(raw: bytes, pos: int, count: int, mask_bytes: int, fields: struct.Struct) -> tuple:
    """``count`` records of a mask then ``fields`` at ``pos``: (the masks as ints, then each
    field's values), each a list, and the position after them. All the records are unpacked
    by one struct call and the columns cut out of its result by strided slices, so no Python
    code runs per record but for a mask wider than 8 bytes (over 64 events): the per-record
    decoding was most of a large image's parse."""
    code, codes = _MASK_CODES.get(mask_bytes), fields.format.lstrip("<")
    flat = struct.unpack_from("<" + ((code or "%ds" % mask_bytes) + codes) * count, raw, pos)
    step = 1 + len(codes)       # values per record: the mask, then one per field
    masks = list(flat[0::step]) if code else [int.from_bytes(mask, "little") for mask in flat[0::step]]
    return (masks,) + tuple(list(flat[i::step]) for i in range(1, step)) + (pos + count * (mask_bytes + fields.size),)


_MASK_CODES = {1: "B", 2: "H", 4: "I", 8: "Q"}     # masks of these widths unpack as integers


class Image:
    """A parsed table image: the canonical tables every runtime interprets.

    Events are numbered 0..E-1 in canonical (name) order; masks are Python ints with bit e for
    event e; ``targets[state_first[g] + rank]`` is the successor of global state g on the
    event whose bit is the rank-th set bit of ``state_defined[g]``."""

    def __init__(self, raw: bytes, num_events: int, num_supervisors: int, controllable: int, public: int,
                 sup_alphabet: List[int], sup_first_state: List[int], sup_num_states: List[int],
                 sup_initial: List[int], state_defined: List[int], state_first: List[int], targets: List[int],
                 probs: Optional[List[int]], names: Optional[List[str]], order: Optional[List[int]] = None,
                 state_order: Optional[List[int]] = None) -> None:
        self.raw = raw
        self.num_events = num_events
        self.num_supervisors = num_supervisors
        self.controllable = controllable
        self.public = public
        self.sup_alphabet = sup_alphabet
        self.sup_first_state = sup_first_state
        self.sup_num_states = sup_num_states
        self.sup_initial = sup_initial
        self.state_defined = state_defined
        self.state_first = state_first
        self.targets = targets
        self.probs = probs
        self.names = names
        self.order = order              # source-file index of each event, or None
        self.state_order = state_order  # source-file number of each (global) state, or None

    @classmethod
    def load(cls, path) -> "Image":
        """Read a ``.svm`` file: at most MAX_IMAGE_SIZE + 1 bytes, so that a huge or endless
        file (``/dev/zero``) is refused without reading it all."""
        with open(path, "rb") as handle:
            return cls.parse(handle.read(MAX_IMAGE_SIZE + 1))

    @classmethod
    def parse(cls, raw: bytes) -> "Image":
        """Check and decode an image; :class:`ImageError` with the code and a message naming the
        first defect. It makes every check of the C reader (svm_validate), in its order."""
        raw = bytes(raw)
        h = read_header(raw)
        if h.num_events == 0 or h.num_supervisors == 0 or h.state_width not in STATE_WIDTHS \
                or h.mask_bytes != (h.num_events + 7) // 8:
            raise _layout_error("image header inconsistent (events %d, mask bytes %d, state width %d, supervisors %d)"
                                % (h.num_events, h.mask_bytes, h.state_width, h.num_supervisors))
        if h.flags & ~KNOWN_FLAGS:
            raise _layout_error("image flags 0x%02x: bits outside 0x%02x are reserved" % (h.flags, KNOWN_FLAGS))
        names = _check_sections(raw, h)
        m = h.mask_bytes
        pos = HEADER_SIZE + 2 * m
        controllable = int.from_bytes(raw[HEADER_SIZE:HEADER_SIZE + m], "little")
        public = int.from_bytes(raw[HEADER_SIZE + m:pos], "little")
        sup_alphabet, sup_first, sup_count, sup_init, pos = _records(raw, pos, h.num_supervisors, m, SUPERVISOR_RECORD)
        state_defined, state_first, pos = _records(raw, pos, h.num_states, m, STATE_RECORD)
        width = h.state_width
        targets = _numbers(raw, pos, h.num_transitions, width)
        pos += h.num_transitions * width
        probs = None
        if h.flags & FLAG_PROBS:
            probs = _numbers(raw, pos, h.num_transitions, PROB.size)
            pos += h.num_transitions * PROB.size
        if names is not None:
            pos += h.num_events + sum(map(len, names))
        order = state_order = None
        if h.flags & FLAG_ORDER:
            order, state_order = _numbers(raw, pos, h.num_events, 1), _numbers(raw, pos + h.num_events, h.num_states, 2)
        image = cls(raw, h.num_events, h.num_supervisors, controllable, public, sup_alphabet, sup_first,
                    sup_count, sup_init, state_defined, state_first, targets, probs, names, order, state_order)
        image._check_indices(h)
        return image

    def _check_indices(self, h: Header) -> None:
        """Every index the step follows stays inside the image, every mask inside E events."""
        if self._indices_fit(h):
            return
        outside = ~((1 << self.num_events) - 1)
        if (self.controllable | self.public) & outside:
            raise _layout_error("image event masks name events beyond the %d events" % self.num_events)
        expected_first = 0
        for s in range(self.num_supervisors):
            first, count = self.sup_first_state[s], self.sup_num_states[s]
            if first != expected_first or count == 0 or self.sup_initial[s] >= count or count > h.num_states - first:
                raise _layout_error("image supervisor %d: states %d..%d (initial %d) do not follow the previous "
                                    "supervisor's inside the %d states" % (s, first, first + count - 1,
                                                                          self.sup_initial[s], h.num_states))
            if self.sup_alphabet[s] & outside:
                raise _layout_error("image supervisor %d's alphabet names events beyond the %d events" % (s, self.num_events))
            for g in range(first, first + count):      # find the first defect, to name it
                defined, succ = self.state_defined[g], self.state_first[g]
                if defined & outside:
                    raise _layout_error("image state %d has transitions on events beyond the %d events" % (g, self.num_events))
                successors = bin(defined).count("1")
                if succ + successors > h.num_transitions:
                    raise _layout_error("image state %d has successors outside the target section" % g)
                for t in range(succ, succ + successors):
                    if self.targets[t] >= count:
                        raise _layout_error("image transition %d leads outside its supervisor %d" % (t, s))
            expected_first = first + count
        if expected_first != h.num_states:
            raise _layout_error("image supervisors hold %d states, the header says %d" % (expected_first, h.num_states))

    def _indices_fit(self, h: Header) -> bool:
        """Whether the image passes _check_indices's checks, in a few C-level passes over the
        whole image for the usual layout (each state's successors right after the previous
        state's); False otherwise, and _check_indices looks supervisor by supervisor and state
        by state for the first defect, to name it."""
        counts, firsts = self.sup_num_states, self.sup_first_state
        if (self.controllable | self.public | max(self.sup_alphabet) | max(self.state_defined, default=0)) \
                >> self.num_events or min(counts) == 0 or any(map(operator.ge, self.sup_initial, counts)):
            return False
        bounds = list(itertools.accumulate(counts, initial=0))
        if bounds[:-1] != firsts or bounds[-1] != h.num_states:
            return False
        ends = list(itertools.accumulate(map(int.bit_count, self.state_defined), initial=self.state_first[0]))
        targets = self.targets
        return (ends[:-1] == self.state_first and ends[-1] <= h.num_transitions
                and all(max(targets[ends[f]:ends[f + c]], default=0) < c for f, c in zip(firsts, counts)))

    def event_name(self, event: int) -> str:
        """``EV_<name>`` when the image carries names, else ``EV_<index>``."""
        return "EV_" + (self.names[event] if self.names is not None else str(event))

    def event_index(self, name: str) -> int:
        """Index of an event given as ``EV_x`` or ``x``; KeyError for an unknown name."""
        if self.names is None:
            raise KeyError("this image carries no event names: bind events by index")
        bare = name[3:] if name.startswith("EV_") else name
        if bare not in self.names:
            raise KeyError("no event named %r in this supervisor" % name)
        return self.names.index(bare)


def _check_sections(raw: bytes, h: Header) -> Optional[List[str]]:
    """The event names (None: no names section), once the sections are known to end exactly
    at the checksum and every name to hold NAME_CHARS only; ImageError (LAYOUT) otherwise."""
    m, end = h.mask_bytes, len(raw) - CRC_SIZE
    pos = (HEADER_SIZE + 2 * m + h.num_supervisors * (m + SUPERVISOR_RECORD.size)
           + h.num_states * (m + STATE_RECORD.size) + h.num_transitions * h.state_width)
    if h.flags & FLAG_PROBS:
        pos += h.num_transitions * PROB.size
    if pos > end:
        raise _layout_error("image sections end at byte %d, past the checksum at byte %d" % (pos, end))
    names = None
    if h.flags & FLAG_NAMES:
        names = []
        for event in range(h.num_events):
            if pos >= end:
                raise _layout_error("image names section ends at event %d of %d" % (event, h.num_events))
            size = raw[pos]
            name = raw[pos + 1:pos + 1 + size]
            if pos + 1 + size > end:
                raise _layout_error("image event %d's name runs past the checksum at byte %d" % (event, end))
            if not NAME_CHARS.issuperset(name):
                raise _layout_error("image event %d's name %r holds characters other than letters, digits and '_'"
                                    % (event, name))
            names.append(name.decode("ascii"))
            pos += 1 + size
    if h.flags & FLAG_ORDER:
        if pos + h.num_events + 2 * h.num_states > end:
            raise _layout_error("image order section runs past the checksum at byte %d" % end)
        if max(raw[pos:pos + h.num_events]) >= h.num_events:
            raise _layout_error("image order section names an event index beyond the %d events" % h.num_events)
        pos += h.num_events + 2 * h.num_states
    if pos != end:
        raise _layout_error("image sections end at byte %d, the checksum is at byte %d" % (pos, end))
    return names
