"""The swarmvm table image format, defined once: docs/image-format.md in code.

Magic, version, header fields and their offsets, flags, section order, limits, the codes a
reader gives a refused image, the checksum, the writer's assembly and the reader. The generator
(generator/compiler/image.py) writes images with :func:`assemble`; the Python VM (swarmvm_vm.py) reads
them with :meth:`Image.parse`. The C and C++ runtimes keep their own constants (a
microcontroller cannot import this file); tests/compiler/test_format_constants.py checks them
against these, and tests/compiler/test_reader_parity.py checks that all three readers give the
same code for the same bad image. Standard library only: it ships beside swarmvm_vm.py, onto a
robot too.
"""

import binascii
import enum
import functools
import itertools
import operator
import os
import stat
import struct
from typing import Any, Dict, List, Literal, NamedTuple, Optional, Tuple, Union

__all__ = ["ErrorCode", "FileKindError", "Header", "Image", "ImageError", "Source", "assemble", "crc16", "read_file",
           "read_header", "write_file"]

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
FLAG_SOURCE = 0x08                  # the source section is present (only with the order section)
KNOWN_FLAGS = FLAG_NAMES | FLAG_PROBS | FLAG_ORDER | FLAG_SOURCE   # any other bit set: refused (ErrorCode.LAYOUT)

MAX_EVENTS = 0xFF
MAX_SUPERVISORS = 0xFF
MAX_STATES = 0xFFFF
MAX_TRANSITIONS = 0xFFFF
STATE_WIDTHS = (1, 2)               # bytes of a target state number

# Sections in image order; "probs", "names" and "order" only with their flag. "order" holds, for
# each event (canonical index), its index in the source file's event list (one byte, below the
# event count), then for each state (global index) its number in the source file (u16): what the
# compatibility API's exact mode steps and reports by (docs/compat.md). "source" (only `swarmvm pack`
# writes it, from a supervisor.yaml) holds the SHA-256 of the file's bytes (SOURCE_DIGEST_SIZE),
# each supervisor's start state (u16, its canonical number of the file's sup_current_state), then
# each event's name as the file writes it (u8 length + bytes): what exact mode starts from and
# registers callbacks by, and what a loader compares with the file beside the image.
SECTIONS = ("controllable", "public", "supervisors", "states", "targets", "probs", "names", "order", "source")
SOURCE_DIGEST_SIZE = 32
SUPERVISOR_RECORD = struct.Struct("<HHH")   # after the alphabet mask: first state, state count, initial state
STATE_RECORD = struct.Struct("<H")          # after the defined mask: index of the first successor
PROB = struct.Struct("<H")                  # Q15
Q15_ONE = 32768

# Bytes an event name may hold (the input languages' rule: letters, digits and '_').
NAME_CHARS = frozenset(b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ_abcdefghijklmnopqrstuvwxyz")
MAX_NAME_LENGTH = 0xFF              # a name's length is one byte

# Streaming an image (docs/image-format.md, "Streaming an image"; swarmvm_stream.h): a chunk is a
# one-byte sequence number and STREAM_CHUNK_DATA bytes of the image, so a stream has at most
# STREAM_MAX_CHUNKS chunks.
STREAM_CHUNK_DATA = 8
STREAM_MAX_CHUNKS = 0x100


@enum.unique
class ErrorCode(enum.IntEnum):
    """Result codes, numbered as swarmvm.h's ``svm_result`` (SVM_OK, SVM_ERR_<NAME>); unique, so that
    two codes given one number fail at import rather than one hiding as the other's alias.

    A reader refuses an image with the first of LENGTH .. LAYOUT that applies, in this order;
    LIMITS is a C build's compile-time maxima; the others come from C API calls, not images."""

    OK = 0
    LENGTH = 1          # shorter than MIN_IMAGE_SIZE, longer than MAX_IMAGE_SIZE, or L != the length
    MAGIC = 2           # not MAGIC
    VERSION = 3         # a format version this reader does not read
    CRC = 4             # checksum mismatch
    LAYOUT = 5          # header inconsistent, sections do not end at L-2, an index or name out of range, or
                        # else what the compiler never writes (a name given twice, ...: docs/image-format.md)
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


# The runtime's one way to read a file (docs/security.md, "The input layer"): every loader of the
# Python runtime (Image.load, SCT's never-stale check, the app's event scripts, a saved learned
# policy) reads through read_file. The runtime ships onto robots without the compiler, so it
# cannot use the compiler's layer (swarmvm.boundary.errors.open_input), which this mirrors: open
# without waiting, regular files only, a bounded read.
MAX_SOURCE_FILE_SIZE = 1 << 20      # the compiler's input limit (swarmvm.boundary.errors.MAX_BYTES)


class FileKindError(OSError):
    """A path the runtime was given to read that is not a regular file (a FIFO, a device, a
    folder, a socket): refused without reading it or waiting on it. ``str()`` is one line."""

    def __init__(self, path: str, kind: str) -> None:
        super().__init__("%s: is %s, not a regular file" % (_printable(path), kind))
        self.filename, self.kind = path, kind

    def __str__(self) -> str:
        return str(self.args[0])


def _printable(text: str) -> str:
    """``text`` with each unprintable character (a newline in a file name) as its escape, so that
    a message naming it stays one line (the compiler's swarmvm.boundary.escape.terminal)."""
    return text if text.isprintable() else "".join(c if c.isprintable() else ascii(c)[1:-1] for c in text)


def _file_kind(mode: int) -> str:
    for test, phrase in ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"),
                         (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return phrase
    return "an unknown kind of file"


def read_file(path: Union[str, "os.PathLike[str]"], limit: int) -> bytes:
    """At most ``limit`` + 1 bytes of the regular file ``path``, so that the caller refuses a
    longer file in its own words (an image: ErrorCode.LENGTH) without reading it all. Opened
    without waiting (O_NONBLOCK: a FIFO with no writer would block a plain open for ever) and
    refused unless a regular file (:class:`FileKindError`: a FIFO, ``/dev/zero``, a folder);
    an OSError as ``open`` gives when it cannot be opened or read."""
    name = os.fspath(path)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0)
    fd = os.open(name, flags)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise FileKindError(name, _file_kind(mode))
        chunks: List[bytes] = []
        left = limit + 1
        while left > 0:
            chunk = os.read(fd, left)
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)
    finally:
        os.close(fd)


def write_file(path: Union[str, "os.PathLike[str]"], data: bytes) -> None:
    """``data`` as the file ``path``, whole or not at all: the runtime's one writer (a saved
    learned policy), the small mirror of the compiler's output layer (swarmvm.boundary.output),
    which a robot does not carry. Written to a temporary file beside it, fsynced, then renamed
    over it; on a failure the temporary file is removed and the old file stays. A new file's
    permissions are what the umask leaves of rw-rw-rw-, a replaced one keeps its own; a path
    that exists and is not a regular file (a FIFO, a device, a folder) is refused."""
    import tempfile
    name = os.fspath(path)
    try:
        info: Optional[os.stat_result] = os.stat(name)
    except FileNotFoundError:
        info = None
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise FileKindError(name, _file_kind(info.st_mode))
    if info is not None:
        mode = stat.S_IMODE(info.st_mode)
    else:
        umask = os.umask(0o022)
        os.umask(umask)
        mode = 0o666 & ~umask
    fd, temporary = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(name)), prefix=".swarmvm-")
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
        os.fsync(fd)
        os.fchmod(fd, mode)
        os.close(fd)
        fd = -1
        os.replace(temporary, name)
    except BaseException:
        if fd >= 0:
            os.close(fd)
        os.unlink(temporary)
        raise


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

    "probs", "names", "order" and "source" are optional and set their flags. :class:`ImageError` (LENGTH) when the
    image would exceed MAX_IMAGE_SIZE."""
    body = b"".join(sections[name] for name in SECTIONS if name in sections)
    length = HEADER_SIZE + len(body) + CRC_SIZE
    if length > MAX_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "table image would be %d bytes, over the format's limit of %d"
                         % (length, MAX_IMAGE_SIZE))
    flags = ((FLAG_PROBS if "probs" in sections else 0) | (FLAG_NAMES if "names" in sections else 0)
             | (FLAG_ORDER if "order" in sections else 0) | (FLAG_SOURCE if "source" in sections else 0))
    mask_bytes = (num_events + 7) // 8
    image = HEADER.pack(*Header(MAGIC, FORMAT_VERSION, flags, num_events, num_supervisors, num_states,
                                num_transitions, state_width, mask_bytes, length)) + body
    return image + struct.pack("<H", crc16(image))


def read_header(raw: bytes) -> Header:
    """The header of ``raw`` once the checks before the layout passed (length, magic, version,
    CRC, in that order); :class:`ImageError` with the first that fails."""
    return Header._make(_checked_fields(bytes(raw)))


def _checked_fields(raw: bytes) -> Tuple[Any, ...]:
    """read_header's checks, giving the header's fields as HEADER unpacks them (a plain tuple:
    Image.parse does not need a Header made). The checksum is checked by its residue: the CRC
    of the bit-reversed image, stored checksum included, is 0 exactly when the checksum is
    right, so a valid image costs one translate and one ``crc_hqx`` call, and the computed
    value the message names is only worked out for a wrong one."""
    size = len(raw)
    if size < MIN_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "image truncated: %d bytes, the header alone needs %d" % (size, MIN_IMAGE_SIZE))
    if size > MAX_IMAGE_SIZE:
        raise ImageError(ErrorCode.LENGTH, "image of %d bytes or more, over the format's maximum of %d"
                         % (size, MAX_IMAGE_SIZE))
    fields = HEADER.unpack_from(raw)
    if fields[_LENGTH] != size:
        raise ImageError(ErrorCode.LENGTH, "image length field says %d bytes, got %d" % (fields[_LENGTH], size))
    if fields[0] != MAGIC:
        raise ImageError(ErrorCode.MAGIC, "not a swarmvm table image (magic %r, expected %r)" % (fields[0], MAGIC))
    if fields[1] != FORMAT_VERSION:
        raise ImageError(ErrorCode.VERSION, "image format version %d, this VM reads version %d"
                         % (fields[1], FORMAT_VERSION))
    if binascii.crc_hqx(raw.translate(_REVERSED), 0xFFFF):      # 0xFFFF: crc16's start, bit-reversed
        end = size - CRC_SIZE
        raise ImageError(ErrorCode.CRC, "image checksum mismatch (stored 0x%04x, computed 0x%04x)"
                         % (_u16(raw, end), crc16(raw[:end])))
    return fields


_LENGTH = Header._fields.index("length")


def _layout_error(message: str) -> ImageError:
    return ImageError(ErrorCode.LAYOUT, message)


def _u16(raw: bytes, pos: int) -> int:
    return raw[pos] | (raw[pos + 1] << 8)


# controllable, public; per supervisor alphabet, first state, state count, initial state; per state
# defined events, first successor; targets; probabilities or None.
_Tables = Tuple[int, int, List[int], List[int], List[int], List[int], List[int], List[int], List[int],
                Optional[List[int]]]


def _tables(raw: bytes, num_supervisors: int, num_states: int, mask_bytes: int, targets_at: int, num_transitions: int,
            state_width: int, probs: bool) -> _Tables:
    """The fixed-size sections decoded, the targets at ``targets_at`` (_Tables: controllable,
    public, then the columns of the supervisor records, of the state records, the targets and the
    probabilities or None, each column a list). One struct call unpacks all the records and their
    columns are cut out of its result by strided slices; targets and probabilities are one array
    each (``list`` of the bytes when a target is one byte). So no Python code runs per record,
    but for masks of other widths than 1, 2, 4 or 8 bytes (one ``int.from_bytes`` each, in C): a
    Python loop per record was most of a large image's parse."""
    code = _MASK_CODES.get(mask_bytes)
    mask = code or "%ds" % mask_bytes
    records = struct.unpack_from("<" + mask * 2 + (mask + "3H") * num_supervisors + (mask + "H") * num_states,
                                 raw, HEADER_SIZE)
    states = 2 + 4 * num_supervisors
    controllable, public = records[0], records[1]
    sup_alphabet, state_defined = list(records[2:states:4]), list(records[states::2])
    if not code:
        controllable, public = int.from_bytes(controllable, "little"), int.from_bytes(public, "little")
        sup_alphabet = list(map(int.from_bytes, sup_alphabet, itertools.repeat(_LITTLE)))
        state_defined = list(map(int.from_bytes, state_defined, itertools.repeat(_LITTLE)))
    targets = (list(raw[targets_at:targets_at + num_transitions]) if state_width == 1
               else list(struct.unpack_from("<%dH" % num_transitions, raw, targets_at)))
    return (controllable, public, sup_alphabet, list(records[3:states:4]), list(records[4:states:4]),
            list(records[5:states:4]), state_defined, list(records[states + 1::2]), targets,
            list(struct.unpack_from("<%dH" % num_transitions, raw, targets_at + num_transitions * state_width))
            if probs else None)


_MASK_CODES = {1: "B", 2: "H", 4: "I", 8: "Q"}     # masks of these widths unpack as integers
_LITTLE: Literal["little"] = "little"


class Image:
    """A parsed table image: the canonical tables every runtime interprets.

    Events are numbered 0..E-1 in canonical (name) order; masks are Python ints with bit e for
    event e; ``targets[state_first[g] + rank]`` is the successor of global state g on the
    event whose bit is the rank-th set bit of ``state_defined[g]``."""

    def __init__(self, raw: bytes, num_events: int, num_supervisors: int, controllable: int, public: int,
                 sup_alphabet: List[int], sup_first_state: List[int], sup_num_states: List[int],
                 sup_initial: List[int], state_defined: List[int], state_first: List[int], targets: List[int],
                 probs: Optional[List[int]], names: Optional[List[str]], order: Optional[List[int]] = None,
                 state_order: Optional[List[int]] = None, source: Optional["Source"] = None) -> None:
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
        self.source = source            # the source section (Source), or None

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Image":
        """Read a ``.svm`` file (:func:`read_file`): a regular file only (a FIFO, a device such
        as ``/dev/zero``, a folder: :class:`FileKindError`), at most MAX_IMAGE_SIZE + 1 bytes of
        it, so that a huge file is refused (LENGTH) without reading it all."""
        return cls.parse(read_file(path, MAX_IMAGE_SIZE))

    @classmethod
    def parse(cls, raw: bytes) -> "Image":
        """Check and decode an image; :class:`ImageError` with the code and a message naming the
        first defect. It makes every check of the C reader (svm_validate), in its order."""
        raw = bytes(raw)
        _, _, flags, events, supervisors, states, transitions, width, mask_bytes, size = _checked_fields(raw)
        if events == 0 or supervisors == 0 or width not in STATE_WIDTHS or mask_bytes != (events + 7) // 8:
            raise _layout_error("image header inconsistent (events %d, mask bytes %d, state width %d, supervisors %d)"
                                % (events, mask_bytes, width, supervisors))
        if flags & ~KNOWN_FLAGS:
            raise _layout_error("image flags 0x%02x: bits outside 0x%02x are reserved" % (flags, KNOWN_FLAGS))
        if flags & FLAG_ORDER and not flags & FLAG_NAMES:
            raise _layout_error("image has an order section without names: the compiler writes it only with them")
        if flags & FLAG_SOURCE and not flags & FLAG_ORDER:
            raise _layout_error("image has a source section without an order section: the compiler writes it only "
                                "with one")
        probs = bool(flags & FLAG_PROBS)
        end = size - CRC_SIZE
        targets_at = (HEADER_SIZE + 2 * mask_bytes + supervisors * (mask_bytes + SUPERVISOR_RECORD.size)
                      + states * (mask_bytes + STATE_RECORD.size))
        pos = targets_at + transitions * (width + (PROB.size if probs else 0))
        if pos > end:
            raise _layout_error("image sections end at byte %d, past the checksum at byte %d" % (pos, end))
        names = order = state_order = source = None
        order_size = events + 2 * states if flags & FLAG_ORDER else 0
        if flags & FLAG_NAMES:
            # (Behind a source section, whose length only its walk gives, the names are walked too.)
            names, pos = (_walk_names(raw, pos, end, events) if flags & FLAG_SOURCE
                          else _names(raw, pos, end - order_size, end, events))
            _check_names_unique(names)
        if flags & FLAG_ORDER:
            order, state_order, pos = _order(raw, pos, end, events, states)
        if flags & FLAG_SOURCE:
            source, pos = _source(raw, pos, end, events, supervisors)
        if pos != end:
            raise _layout_error("image sections end at byte %d, the checksum is at byte %d" % (pos, end))
        image = cls(raw, events, supervisors, *_tables(raw, supervisors, states, mask_bytes, targets_at, transitions,
                                                       width, probs), names, order, state_order, source)
        image._check_indices(states, transitions)
        return image

    def _check_indices(self, num_states: int, num_transitions: int) -> None:
        """Every index the step follows stays inside the image, every mask inside E events."""
        if self._indices_fit(num_states, num_transitions):
            return
        outside = ~((1 << self.num_events) - 1)
        if (self.controllable | self.public) & outside:
            raise _layout_error("image event masks name events beyond the %d events" % self.num_events)
        expected_first = expected_succ = 0
        for s in range(self.num_supervisors):
            first, count = self.sup_first_state[s], self.sup_num_states[s]
            if first != expected_first or count == 0 or self.sup_initial[s] != 0 or count > num_states - first:
                raise _layout_error("image supervisor %d: states %d..%d (initial %d) do not follow the previous "
                                    "supervisor's inside the %d states from its initial state 0"
                                    % (s, first, first + count - 1, self.sup_initial[s], num_states))
            if self.sup_alphabet[s] & outside:
                raise _layout_error("image supervisor %d's alphabet names events beyond the %d events" % (s, self.num_events))
            for g in range(first, first + count):      # find the first defect, to name it
                defined, succ = self.state_defined[g], self.state_first[g]
                if defined & outside:
                    raise _layout_error("image state %d has transitions on events beyond the %d events" % (g, self.num_events))
                if defined & ~self.sup_alphabet[s]:
                    raise _layout_error("image state %d has transitions on events outside its supervisor %d's alphabet"
                                        % (g, s))
                if succ != expected_succ:
                    raise _layout_error("image state %d's successors start at target %d, not right after the previous "
                                        "state's (%d)" % (g, succ, expected_succ))
                successors = bin(defined).count("1")
                if succ + successors > num_transitions:
                    raise _layout_error("image state %d has successors outside the target section" % g)
                expected_succ = succ + successors
                for t in range(succ, succ + successors):
                    if self.targets[t] >= count:
                        raise _layout_error("image transition %d leads outside its supervisor %d" % (t, s))
            expected_first = first + count
        if expected_first != num_states:
            raise _layout_error("image supervisors hold %d states, the header says %d" % (expected_first, num_states))
        if expected_succ != num_transitions:
            raise _layout_error("image states have %d successors, the header says %d transitions: targets no state "
                                "reaches" % (expected_succ, num_transitions))

    def _indices_fit(self, num_states: int, num_transitions: int) -> bool:
        """Whether the image passes _check_indices's checks, in a few C-level passes over the
        whole image; False otherwise, and _check_indices looks supervisor by supervisor and state
        by state for the first defect, to name it. (A count of 0 fails the check of the first
        states: two supervisors would start at the same state.)"""
        counts = self.sup_num_states
        if any(self.sup_initial) or 0 in counts:
            return False
        bounds = [0, *itertools.accumulate(counts)]
        if bounds.pop() != num_states or bounds != self.sup_first_state:
            return False
        if (self.controllable | self.public | max(self.sup_alphabet) | max(self.state_defined)) >> self.num_events:
            return False
        defined = self.state_defined
        if any(functools.reduce(operator.or_, defined[f:f + c]) & ~alphabet
               for f, c, alphabet in zip(bounds, counts, self.sup_alphabet)):
            return False
        ends = [*itertools.accumulate(map(int.bit_count, defined), initial=0)]
        last = ends.pop()
        if last != num_transitions or ends != self.state_first:
            return False
        # Only a supervisor with no more states than the largest target a state follows can have
        # one outside it: usually none or few are looked at one by one.
        targets = self.targets
        top = max(targets[ends[0]:last], default=0)
        if top < min(counts):
            return True
        ends.append(last)
        return all(max(targets[ends[f]:ends[f + c]], default=0) < c for f, c in zip(bounds, counts) if c <= top)

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


def _names(raw: bytes, pos: int, stop: int, end: int, events: int) -> Tuple[List[str], int]:
    """The event names at ``pos`` and the position after them, once each is known to end before
    the checksum at ``end`` and to hold NAME_CHARS only; ImageError (LAYOUT) otherwise.

    A well-formed section that ends at ``stop`` (where the sections after it must begin) is
    split in a few C-level calls, without a Python step per name: its bytes that cannot be in
    a name are then exactly the length bytes, and the pieces between them the names, each as
    long as its length byte says. Any other section (a defect, or a name whose length byte is
    also a name character: 48 characters or more) is walked name by name (_walk_names)."""
    section = raw[pos:stop]
    lengths = section.translate(None, _NAME_BYTES)
    names = section.translate(_NAME_SPLIT).decode().split("\0")
    if len(lengths) == events and [*map(len, names)] == [0, *lengths]:
        return names[1:], stop
    return _walk_names(raw, pos, end, events)


_NAME_BYTES = bytes(sorted(NAME_CHARS))
# Each byte that cannot be in a name (a length byte) to NUL, the others to themselves.
_NAME_SPLIT = bytes(value if value in NAME_CHARS else 0 for value in range(256))


def _walk_names(raw: bytes, pos: int, end: int, events: int) -> Tuple[List[str], int]:
    """_names one name at a time: the names and the position after them, or ImageError (LAYOUT)
    naming the first defect."""
    names = []
    for event in range(events):
        if pos >= end:
            raise _layout_error("image names section ends at event %d of %d" % (event, events))
        size = raw[pos]
        name = raw[pos + 1:pos + 1 + size]
        if pos + 1 + size > end:
            raise _layout_error("image event %d's name runs past the checksum at byte %d" % (event, end))
        if not NAME_CHARS.issuperset(name):
            raise _layout_error("image event %d's name %r holds characters other than letters, digits and '_'"
                                % (event, name))
        names.append(name.decode("ascii"))
        pos += 1 + size
    return names, pos


def _check_names_unique(names: List[str]) -> None:
    """ImageError (LAYOUT) naming the first name given twice: the compiler writes each event's
    name once, and a name given twice would make binding by name ambiguous."""
    if len(set(names)) == len(names):
        return
    first: Dict[str, int] = {}
    for event, name in enumerate(names):
        if name in first:
            raise _layout_error("image event %d's name %r is event %d's too: each name is given once"
                                % (event, name, first[name]))
        first[name] = event


def _order(raw: bytes, pos: int, end: int, events: int, states: int) -> Tuple[List[int], List[int], int]:
    """The order section at ``pos``: each event's index in the source file, each state's
    number there, and the position after it; ImageError (LAYOUT) when it runs past the
    checksum at ``end`` or its event indices are not each of 0..E-1 once (a permutation)."""
    after = pos + events + 2 * states
    if after > end:
        raise _layout_error("image order section runs past the checksum at byte %d" % end)
    order = list(raw[pos:pos + events])
    if max(order) >= events:
        raise _layout_error("image order section names an event index beyond the %d events" % events)
    if len(set(order)) != events:
        raise _layout_error("image order section names an event index twice: not a permutation of the %d events"
                            % events)
    return order, list(struct.unpack_from("<%dH" % states, raw, pos + events)), after


class Source(NamedTuple):
    """The source section: what exact mode needs of the supervisor file beyond its order."""

    digest: bytes               # SHA-256 of the supervisor file's bytes
    start: List[int]            # each supervisor's start state (canonical local number)
    written: List[str]          # each event's name as the file writes it (canonical event order)


def _source(raw: bytes, pos: int, end: int, events: int, supervisors: int) -> Tuple[Source, int]:
    """The source section at ``pos`` and the position after it; ImageError (LAYOUT) when it runs
    past the checksum at ``end``. Its bytes are only bounds-checked, as every reader does (the C
    reader skips it): the compatibility layers check a start state against its supervisor."""
    names_at = pos + SOURCE_DIGEST_SIZE + 2 * supervisors
    if names_at > end:
        raise _layout_error("image source section runs past the checksum at byte %d" % end)
    start = list(struct.unpack_from("<%dH" % supervisors, raw, pos + SOURCE_DIGEST_SIZE))
    written, at = [], names_at
    for event in range(events):
        if at >= end or at + 1 + raw[at] > end:
            raise _layout_error("image source section: event %d's written name runs past the checksum at byte %d"
                                % (event, end))
        written.append(raw[at + 1:at + 1 + raw[at]].decode("latin-1"))
        at += 1 + raw[at]
    return Source(raw[pos:pos + SOURCE_DIGEST_SIZE], start, written), at
