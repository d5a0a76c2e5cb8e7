"""The three image readers refuse the same bad image with the same code, and accept the good ones.

Many bad images (truncated, bad magic, version, checksum, and every layout violation with a
valid, recomputed checksum: absurd counts, sections that do not end at the checksum, bad
names, supervisors and states out of range, targets outside their supervisor, mask bits beyond
the events) go through the Python reader (swarmvm_format.Image.parse), the C reader (svm_load,
runtime_c/swarmvm.c, built with gcc) and the C++ reader (swarmvm::Image::parse, built with g++),
each expecting the code the format definition gives it (swarmvm_format.ErrorCode = swarmvm.h's
SVM_ERR_*). The C and C++ programs are built with AddressSanitizer and UBSan, so a reader that
looks past an image's last byte fails the test too."""

import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from swarmvm.compiler.image import pack
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_C, RUNTIME_CPP, RUNTIME_PY_DIR, image_format

F = image_format()
E = F.ErrorCode
HERE = Path(__file__).resolve().parent
CORPUS = HERE.parent / "corpus"
SANITIZE = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g"]
# Limits at the format's own maxima: an image the format allows is never over this build's.
C_LIMITS = ["-DSVM_MAX_EVENTS=255", "-DSVM_MAX_SUPERVISORS=255", "-DSVM_MAX_STATES=65535"]


@pytest.fixture(scope="module")
def readers(tmp_path_factory):
    """The C and C++ reader programs, built once."""
    out = tmp_path_factory.mktemp("readers")
    c_exe, cpp_exe = out / "reader_check_c", out / "reader_check_cpp"
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", *SANITIZE, *C_LIMITS,
                    "-I", str(RUNTIME_C), str(HERE / "reader_check.c"), str(RUNTIME_C / "swarmvm.c"),
                    "-o", str(c_exe)], check=True)
    subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic", *SANITIZE,
                    "-I", str(RUNTIME_CPP), str(HERE / "reader_check.cpp"), "-o", str(cpp_exe)], check=True)
    return c_exe, cpp_exe


def _codes(exe, paths):
    run = subprocess.run([str(exe), *map(str, paths)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-2000:]
    return [int(line) for line in run.stdout.split()]


def _python_code(raw):
    try:
        F.Image.parse(raw)
    except F.ImageError as exc:
        return exc.code
    return E.OK


# ---- building images ------------------------------------------------------------------------

def _corpus(name, names=True):
    return compile_inputs([str(next(CORPUS.glob("*/%s.yaml" % name)))], names=names).image


def _reseal(raw):
    """The image with its checksum recomputed (its length field untouched)."""
    body = bytes(raw[:-F.CRC_SIZE])
    return body + F.crc16(body).to_bytes(F.CRC_SIZE, "little")


def _header(raw, **fields):
    """The image with header fields replaced, resealed."""
    header = F.Header.unpack(raw)._replace(**fields)
    return _reseal(F.HEADER.pack(*header) + raw[F.HEADER_SIZE:])


def _resized(raw, body):
    """``body`` (an image without checksum) with its length field fitted, resealed."""
    body = bytearray(body)
    at = F.OFFSETS["length"]
    body[at:at + 2] = (len(body) + F.CRC_SIZE).to_bytes(2, "little")
    return _reseal(bytes(body) + b"\0\0")


def _tables(raw):
    """The tables of a good image as the writer (swarmvm.compiler.image.pack) takes them, to edit."""
    image = F.Image.parse(raw)
    return SimpleNamespace(
        num_events=image.num_events, num_supervisors=image.num_supervisors,
        num_states=len(image.state_defined), num_transitions=len(image.targets),
        mask_bytes=(image.num_events + 7) // 8, state_width=raw[F.OFFSETS["state_width"]],
        controllable=image.controllable, public=image.public, sup_alphabet=list(image.sup_alphabet),
        sup_first_state=list(image.sup_first_state), sup_num_states=list(image.sup_num_states),
        sup_initial=list(image.sup_initial), state_defined=list(image.state_defined),
        state_first=list(image.state_first), targets=list(image.targets), probs=image.probs,
        names=list(image.names or []))


def _edited(raw, edit, names=True):
    """A good image's tables, edited by ``edit(tables)``, written by the real writer."""
    tables = _tables(raw)
    edit(tables)
    return pack(tables, "test", names=names)


def _set(**values):
    return lambda t: t.__dict__.update(values)


def _item(field, index, value):
    return lambda t: getattr(t, field).__setitem__(index, value(t) if callable(value) else value)


def _first_successor_state(t):
    """A global state with at least one transition."""
    return next(g for g, d in enumerate(t.state_defined) if d)


def _successors_past_targets(t):
    """A state whose successors run one past the target section."""
    g = _first_successor_state(t)
    t.state_first[g] = t.num_transitions - bin(t.state_defined[g]).count("1") + 1


def _pad_bit(t):
    """The lowest mask bit beyond the events (the tables must have E % 8 != 0)."""
    assert t.num_events % 8, "needs an image with unused mask bits"
    return 1 << t.num_events


def _consecutive_states_with_successors(t):
    """Two states g, g + 1 of one supervisor, each with transitions."""
    for first, count in zip(t.sup_first_state, t.sup_num_states):
        for g in range(first, first + count - 1):
            if t.state_defined[g] and t.state_defined[g + 1]:
                return g
    raise AssertionError("needs two consecutive states with transitions")


def _overlapping_successors(t):
    """State g + 1 reads state g's targets: every index stays in range, no state reads the
    targets after them."""
    g = _consecutive_states_with_successors(t)
    t.state_first[g + 1] = t.state_first[g]


def _defined_outside_alphabet(t):
    """A supervisor's alphabet loses an event one of its states has a transition on."""
    g = _first_successor_state(t)
    s = max(k for k, first in enumerate(t.sup_first_state) if first <= g)
    t.sup_alphabet[s] &= ~(t.state_defined[g] & -t.state_defined[g])


def _names_at(raw):
    image = F.Image.parse(raw)
    return len(raw) - F.CRC_SIZE - sum(1 + len(n) for n in image.names)


def good_images():
    """Images every reader accepts: corpus images with and without names, with probabilities,
    with 8 events (no unused mask bits), an empty name, two-byte state numbers,
    with the order section (and another permutation in it)."""
    names = ["energy_worker", "network_worker", "probabilistic_example", "flipflop_S", "uav", "capbot_demo"]
    images = {name: _corpus(name) for name in names}
    images["energy_worker_no_names"] = _corpus("energy_worker", names=False)
    images["energy_worker_wide_states"] = _edited(images["energy_worker"], _set(state_width=2))
    images["probabilistic_no_names"] = _corpus("probabilistic_example", names=False)
    ordered = compile_inputs([str(next(CORPUS.glob("*/energy_worker.yaml")))]).ordered_image
    images["energy_worker_ordered"] = ordered
    swapped = bytearray(ordered)        # another permutation of the events in the order section
    at = len(ordered) - F.CRC_SIZE - ordered[F.OFFSETS["num_events"]] - 2 * F.Header.unpack(ordered).num_states
    swapped[at:at + 2] = swapped[at + 1], swapped[at]
    images["energy_worker_order_permuted"] = _reseal(bytes(swapped))
    return images


def bad_images():
    """{case: (image, expected code)}."""
    good = _corpus("energy_worker")                 # 10 events: mask bits 10..15 unused
    probs = _corpus("probabilistic_example")
    t = _tables(good)
    events, length = t.num_events, len(good)
    names_at = _names_at(good)
    end = length - F.CRC_SIZE
    cases = {
        # length: first of all checks
        "empty": (b"", E.LENGTH),
        "one_byte": (b"S", E.LENGTH),
        "header_only": (good[:F.MIN_IMAGE_SIZE - 1], E.LENGTH),
        "truncated": (good[:-1], E.LENGTH),
        "trailing_byte": (good + b"\0", E.LENGTH),
        "length_field_small": (_header(good, length=length - 1), E.LENGTH),
        "length_field_zero": (_header(good, length=0), E.LENGTH),
        "bad_magic_and_length": (_header(good, magic=b"XVMI", length=length + 1), E.LENGTH),
        "all_zeros": (bytes(64), E.LENGTH),
        "all_ones": (b"\xff" * 64, E.LENGTH),
        # magic
        "magic": (_header(good, magic=b"XVMI"), E.MAGIC),
        "magic_lower_case": (_header(good, magic=b"svmi"), E.MAGIC),
        "magic_last_byte": (_header(good, magic=b"SVMJ"), E.MAGIC),
        "magic_and_version": (_header(good, magic=b"SVMX", version=9), E.MAGIC),
        # version
        "version_0": (_header(good, version=0), E.VERSION),
        "version_2": (_header(good, version=F.FORMAT_VERSION + 1), E.VERSION),
        "version_255": (_header(good, version=255), E.VERSION),
        "version_and_crc": (_header(good, version=2)[:-1] + b"\0", E.VERSION),
        # checksum
        "crc_body_bit": (good[:20] + bytes([good[20] ^ 1]) + good[21:], E.CRC),
        "crc_stored": (good[:-1] + bytes([good[-1] ^ 0x80]), E.CRC),
        "crc_and_layout": (F.HEADER.pack(b"SVMI", 1, 0, 0, 0, 0, 0, 0, 0, 20) + b"\0\0\0\0", E.CRC),
        # header consistency
        "no_events": (_header(good, num_events=0, mask_bytes=0), E.LAYOUT),
        "no_supervisors": (_header(good, num_supervisors=0), E.LAYOUT),
        "state_width_0": (_header(good, state_width=0), E.LAYOUT),
        "state_width_3": (_header(good, state_width=3), E.LAYOUT),
        "mask_bytes_small": (_header(good, mask_bytes=1), E.LAYOUT),
        "mask_bytes_large": (_header(good, mask_bytes=3), E.LAYOUT),
        "events_past_mask": (_header(good, num_events=17), E.LAYOUT),
        "reserved_flag_bit": (_header(good, flags=good[F.OFFSETS["flags"]] | 0x04), E.LAYOUT),
        "reserved_flag_top": (_header(good, flags=good[F.OFFSETS["flags"]] | 0x80), E.LAYOUT),
        "probs_flag_without_section": (_header(good, flags=good[F.OFFSETS["flags"]] | F.FLAG_PROBS), E.LAYOUT),
        "names_flag_off": (_header(good, flags=good[F.OFFSETS["flags"]] & ~F.FLAG_NAMES), E.LAYOUT),
        "probs_flag_off": (_header(probs, flags=probs[F.OFFSETS["flags"]] & ~F.FLAG_PROBS), E.LAYOUT),
        # counts that do not fit the image
        "states_plus_one": (_header(good, num_states=t.num_states + 1), E.LAYOUT),
        "states_minus_one": (_header(good, num_states=t.num_states - 1), E.LAYOUT),
        "transitions_plus_one": (_header(good, num_transitions=t.num_transitions + 1), E.LAYOUT),
        "transitions_minus_one": (_header(good, num_transitions=t.num_transitions - 1), E.LAYOUT),
        "absurd_states": (_header(good, num_states=0xFFFF), E.LAYOUT),
        "absurd_transitions": (_header(good, num_transitions=0xFFFF), E.LAYOUT),
        "absurd_supervisors": (_header(good, num_supervisors=255), E.LAYOUT),
        "absurd_everything": (_header(good, num_events=255, mask_bytes=32, num_supervisors=255, num_states=0xFFFF,
                                      num_transitions=0xFFFF, state_width=2, flags=3), E.LAYOUT),
        "header_and_checksum_only": (_resized(good, good[:F.HEADER_SIZE]), E.LAYOUT),
        # sections that do not end at the checksum
        "names_short": (_resized(good, good[:end - 1]), E.LAYOUT),
        "byte_before_checksum": (_resized(good, good[:end] + b"A"), E.LAYOUT),
        "name_length_past_checksum": (_reseal(good[:names_at] + b"\xff" + good[names_at + 1:]), E.LAYOUT),
        "name_length_plus_one": (_reseal(good[:names_at] + bytes([good[names_at] + 1]) + good[names_at + 1:]),
                                 E.LAYOUT),
        "names_missing": (_resized(good, good[:names_at]), E.LAYOUT),
        # supervisors and states out of range (valid header, sections and checksum)
        "sup_first_state_gap": (_edited(good, _item("sup_first_state", 1, lambda t: t.sup_first_state[1] + 1)),
                                E.LAYOUT),
        "sup_first_state_overlap": (_edited(good, _item("sup_first_state", 1, lambda t: t.sup_first_state[1] - 1)),
                                    E.LAYOUT),
        "sup_first_state_nonzero": (_edited(good, _item("sup_first_state", 0, 1)), E.LAYOUT),
        "sup_no_states": (_edited(good, _item("sup_num_states", 0, 0)), E.LAYOUT),
        "sup_states_past_end": (_edited(good, _item("sup_num_states", t.num_supervisors - 1,
                                                    lambda t: t.sup_num_states[-1] + 1)), E.LAYOUT),
        "sup_states_short": (_edited(good, _item("sup_num_states", t.num_supervisors - 1,
                                                 lambda t: t.sup_num_states[-1] - 1)), E.LAYOUT),
        "sup_initial_out_of_range": (_edited(good, _item("sup_initial", 0, lambda t: t.sup_num_states[0])), E.LAYOUT),
        "sup_initial_absurd": (_edited(good, _item("sup_initial", 0, 0xFFFF)), E.LAYOUT),
        "extra_state": (_edited(good, lambda t: (t.state_defined.append(0), t.state_first.append(0),
                                                 t.__dict__.update(num_states=t.num_states + 1))), E.LAYOUT),
        "state_first_past_targets": (_edited(good, _item("state_first", 0, lambda t: t.num_transitions + 1)),
                                     E.LAYOUT),
        "state_successors_past_targets": (_edited(good, _successors_past_targets), E.LAYOUT),
        "state_first_absurd": (_edited(good, _item("state_first", 0, 0xFFFF)), E.LAYOUT),
        "target_out_of_supervisor": (_edited(good, _item("targets", 0, lambda t: t.sup_num_states[0])), E.LAYOUT),
        "target_absurd_wide": (_edited(good, lambda t: (t.__dict__.update(state_width=2),
                                                        t.targets.__setitem__(-1, 0xFFFF))), E.LAYOUT),
        "target_absurd_narrow": (_edited(good, _item("targets", -1, 0xFF)), E.LAYOUT),
        # mask bits beyond the events
        "controllable_beyond_events": (_edited(good, lambda t: t.__dict__.update(
            controllable=t.controllable | _pad_bit(t))), E.LAYOUT),
        "public_beyond_events": (_edited(good, lambda t: t.__dict__.update(public=t.public | 0x8000)), E.LAYOUT),
        "alphabet_beyond_events": (_edited(good, _item("sup_alphabet", 1, lambda t: t.sup_alphabet[1] | _pad_bit(t))),
                                   E.LAYOUT),
        "defined_beyond_events": (_edited(good, _item("state_defined", 0, lambda t: t.state_defined[0] | 0x8000)),
                                  E.LAYOUT),
    }
    assert events % 8 != 0
    cases.update(uncompiled_images())
    return cases


def uncompiled_images():
    """{case: (image, LAYOUT)}: images every check above passes (sound sections, indices in range,
    a valid checksum) but that the compiler could not have written: a name given twice (next to
    each other, or apart), an order section without names or whose event indices are not a
    permutation, a supervisor starting elsewhere than its state 0, a transition on an event
    outside its supervisor's alphabet, states whose successors overlap or leave targets no state
    reads. The readers of before issue 23 accepted each (a duplicate name passed `swarmvm check`)."""
    good = _corpus("energy_worker")
    t = _tables(good)
    compiled = compile_inputs([str(next(CORPUS.glob("*/energy_worker.yaml")))])
    ordered = F.Image.parse(compiled.ordered_image)
    order = (list(ordered.order), list(ordered.state_order))

    def names(edit):
        return lambda t: t.__dict__.update(names=edit(list(t.names)))

    return {
        "name_given_twice": (_edited(good, names(lambda n: [n[0], n[0], *n[2:]])), E.LAYOUT),
        "name_given_twice_last": (_edited(good, names(lambda n: [*n[:-1], n[-2]])), E.LAYOUT),
        "name_given_twice_apart": (_edited(good, names(lambda n: [*n[:-1], n[0]])), E.LAYOUT),
        "empty_name_twice": (_edited(good, names(lambda n: ["", "", *n[2:]])), E.LAYOUT),
        "order_without_names": (pack(t, "test", names=False, order=order), E.LAYOUT),
        "order_event_twice": (pack(t, "test", order=([order[0][0], *order[0][:-1]], order[1])), E.LAYOUT),
        "sup_initial_not_zero": (_edited(good, _item("sup_initial", 0, 1)), E.LAYOUT),
        "defined_outside_alphabet": (_edited(good, _defined_outside_alphabet), E.LAYOUT),
        "successors_overlap": (_edited(good, _overlapping_successors), E.LAYOUT),
        "target_no_state_reads": (_edited(good, lambda t: (t.targets.append(0), t.__dict__.update(
            num_transitions=t.num_transitions + 1))), E.LAYOUT),
    }


def name_char_images():
    """The first event's name with each byte value in turn as its first character: accepted
    exactly for letters, digits and '_'."""
    good = _corpus("energy_worker")
    at = _names_at(good) + 1
    assert good[at - 1] > 0, "the first event needs a name"
    return {"name_byte_%02x" % b: (_reseal(good[:at] + bytes([b]) + good[at + 1:]),
                                   E.OK if b in F.NAME_CHARS else E.LAYOUT) for b in range(256)}


def all_cases():
    cases = {name: (raw, E.OK) for name, raw in good_images().items()}
    cases.update(bad_images())
    cases.update(name_char_images())
    return cases


def test_bad_images_are_really_what_they_say():
    """The edited images differ from their good image only where meant: their checksum is
    valid unless the case is about it, so the layout cases reach the layout checks."""
    for name, (raw, code) in bad_images().items():
        if code == E.LAYOUT:
            assert len(raw) >= F.MIN_IMAGE_SIZE and F.Header.unpack(raw).length == len(raw), name
            assert F.crc16(raw[:-2]) == int.from_bytes(raw[-2:], "little"), name


@pytest.mark.slow      # builds the C and C++ readers with sanitizers
def test_every_reader_gives_the_same_code(readers, tmp_path):
    c_exe, cpp_exe = readers
    cases = all_cases()
    paths = []
    for k, (name, (raw, _)) in enumerate(cases.items()):
        paths.append(tmp_path / ("%03d_%s.svm" % (k, name)))
        paths[-1].write_bytes(raw)
    expected = {name: int(code) for name, (_, code) in cases.items()}
    python = {name: int(_python_code(raw)) for name, (raw, _) in cases.items()}
    c = dict(zip(cases, _codes(c_exe, paths)))
    cpp = dict(zip(cases, _codes(cpp_exe, paths)))
    assert python == expected
    assert c == expected
    assert cpp == expected
    assert sum(code == E.OK for code in expected.values()) >= 11 + 63    # good images, name characters


def test_python_messages_name_the_defect():
    cases = bad_images()
    for name, needle in [("truncated", "length field"), ("magic", "not a swarmvm table image"),
                         ("name_given_twice", "event 1's name 'atCharger' is event 0's too"),
                         ("order_without_names", "order section without names"),
                         ("order_event_twice", "not a permutation"),
                         ("defined_outside_alphabet", "outside its supervisor 0's alphabet"),
                         ("target_no_state_reads", "targets no state reaches"),
                         ("version_2", "format version 2"), ("crc_stored", "checksum mismatch"),
                         ("target_out_of_supervisor", "leads outside its supervisor"),
                         ("sup_first_state_gap", "supervisor 1"), ("defined_beyond_events", "beyond the 10 events")]:
        with pytest.raises(F.ImageError, match=needle):
            F.Image.parse(cases[name][0])


def test_oversized_image_is_refused_for_its_length(tmp_path):
    """Python refuses more than the format's maximum image size, in memory and as a file."""
    big = bytes(F.MAX_IMAGE_SIZE + 1)
    assert _python_code(big) == E.LENGTH
    path = tmp_path / "big.svm"
    path.write_bytes(big + bytes(100))
    with pytest.raises(F.ImageError, match="over the format's maximum") as refused:
        F.Image.load(path)
    assert refused.value.code == E.LENGTH


ENDLESS = Path("/dev/zero")


@pytest.mark.slow
@pytest.mark.skipif(not ENDLESS.exists(), reason="needs /dev/zero (a Unix system)")
def test_an_endless_file_is_refused_in_bounded_memory(readers, tmp_path):
    """/dev/zero, limited to 300 MB (an unbounded read would exceed it): the Python and C++
    runtimes' loaders (their input layers, swarmvm_format.read_file and read_regular_file) and
    the command line (swarmvm.boundary.errors.open_input) each refuse it in one line without
    reading it, as a device, even under an image's name. (A regular file is read to the maximum
    image size + 1 bytes and refused with LENGTH: the tests above and
    tests/boundary/test_runtime_loaders.py.)"""
    limit = 300 * 1024 * 1024
    probe = ("import resource, sys\n"
             "resource.setrlimit(resource.RLIMIT_AS, (%d, %d))\n"
             "sys.path.insert(0, %r)\n"
             "import swarmvm_format as f\n"
             "try:\n"
             "    f.Image.load('/dev/zero')\n"
             "except f.FileKindError as exc:\n"
             "    print(exc)\n" % (limit, limit, str(RUNTIME_PY_DIR)))
    run = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60)
    assert (run.returncode, run.stdout.strip()) == (0, "/dev/zero: is a character device, not a regular file"), \
        run.stderr[-1000:]
    image = tmp_path / "zero.svm"
    image.symlink_to(ENDLESS)
    cli = ("import resource, sys\n"
           "resource.setrlimit(resource.RLIMIT_AS, (%d, %d))\n"
           "from swarmvm.cli.commands import main\n"
           "main(['check', %r])\n" % (2 * limit, 2 * limit, str(image)))
    run = subprocess.run([sys.executable, "-c", cli], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and run.stderr == "swarmvm: error: %s: is a character device, not a regular file\n" % (
        image), run.stderr[-1000:]
    _, cpp_exe = readers
    # (AddressSanitizer reserves terabytes of address space: its own RSS limit bounds the C++ run.)
    run = subprocess.run([str(cpp_exe), "--load=/dev/zero"], capture_output=True, text=True, timeout=60,
                         env={"ASAN_OPTIONS": "hard_rss_limit_mb=300"})
    assert (run.returncode, run.stdout.strip()) == (0, "-1"), run.stderr[-1000:]


def test_the_command_line_refuses_every_bad_image_in_one_line_and_runs_every_good_one(tmp_path):
    """`swarmvm check` accepts exactly what the C runtime accepts (the codes above), and `trace`
    on a refused image is the same one line (it once failed with IndexError), never a
    traceback; an accepted one is checked, and traced (or, without names, refused in one line:
    a script names events)."""
    from click.testing import CliRunner

    from swarmvm.cli.commands import main
    script = tmp_path / "empty.script"
    script.write_text("-\n")
    for name, (raw, code) in all_cases().items():
        image = tmp_path / (name + ".svm")
        image.write_bytes(raw)
        for command in (["check", str(image)], ["trace", str(image), "--script", str(script)]):
            result = CliRunner().invoke(main, command)
            if code == E.OK and (command[0] == "check" or "no_names" not in name):
                assert result.exit_code == 0, (name, command, result.output)
            elif code == E.OK:
                assert result.exit_code == 2 and result.stderr.endswith("carries no event names; scripts name events\n")
            else:
                assert result.exit_code == 2 and result.stderr.count("\n") == 1, (name, command, result.output)
                assert result.stderr.startswith("swarmvm: error: %s: " % image), (name, result.stderr)
