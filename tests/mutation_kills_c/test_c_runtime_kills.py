"""Tests written against mutants of runtime_c/swarmvm.c that the host tests let survive
(`make mutation-c`, scripts/mutation_c.py, docs/mutation.md). Each builds a small program over
the C runtime with the host gcc and the project's warnings and compares what it prints with the
Python reference."""

import dataclasses
import random
import subprocess
from pathlib import Path

import pytest

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import SUPERVISORS, batch, supervisor_yaml
from conformance.test_c_host import _with_names
from compiler.test_reader_parity import _edited, _set
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_C, image_format

F = image_format()


def run_c(tmp_path: Path, body: str, defines: tuple[str, ...] = (), prelude: str = "") -> list[str]:
    """The lines printed by a program whose main() is ``body`` (swarmvm.h, stdio.h and stdint.h
    included, then ``prelude``), built with swarmvm.c."""
    program = tmp_path / "probe.c"
    program.write_text("#include <stdint.h>\n#include <stdio.h>\n#include \"swarmvm.h\"\n\n%s\n"
                       "int main(void)\n{\n%s\n    return 0;\n}\n" % (prelude, body))
    exe = tmp_path / "probe"
    subprocess.run(["gcc", *c_harness.WARNINGS, "-O1", *defines, "-I", str(RUNTIME_C), str(program), str(RUNTIME_C / "swarmvm.c"),
                    "-o", str(exe)], check=True, capture_output=True, text=True)
    return subprocess.run([str(exe)], check=True, capture_output=True, text=True, timeout=30).stdout.split()


def c_array(name: str, data: bytes) -> str:
    return "    static const uint8_t %s[] = {%s};" % (name, ", ".join(str(b) for b in data) or "0")


def test_the_checksum_of_each_byte_from_each_start_is_the_reference(tmp_path):
    """svm_crc16_update (the learned-parameter store's records) over every byte value, from the
    initial value and from a sum with its low byte set: every entry of the host's one-byte CRC
    table (the mutation run leaves constant tables' entries out: this pins that one whole)."""
    printed = run_c(tmp_path, "    unsigned b;\n    for (b = 0; b < 256u; b++) {\n"
                              "        printf(\"%u %u\\n\", svm_crc16_update(SVM_CRC16_INIT, (uint8_t)b),"
                              " svm_crc16_update(0x12A5u, (uint8_t)b));\n    }")
    expected = []
    for b in range(256):
        expected += [str(F.crc16(bytes([b]))), str(F.crc16(bytes([b]), 0x12A5))]
    assert printed == expected


def twenty_event_model(tmp_path: Path) -> str:
    """A supervisor.yaml of 20 events (masks of 3 bytes; even events controllable, every third
    public) in two local supervisors, transitions drawn with a fixed seed."""
    rng = random.Random(29)
    events = ["e%d" % k for k in range(20)]
    alphabets = [set(events), set(events[4:16])]
    states = [[[(e, rng.randrange(count)) for e in events if e in alphabet and rng.random() < 0.6]
               for _ in range(count)] for alphabet, count in zip(alphabets, (4, 3))]
    path = tmp_path / "twenty.yaml"
    path.write_text(supervisor_yaml(events, [k % 2 == 0 for k in range(20)], alphabets, states,
                                    public=[k % 3 == 0 for k in range(20)]))
    return str(path)


@pytest.mark.parametrize("build", [pytest.param((True, ()), id="exact-3-byte-masks"),
                                   pytest.param((False, ()), id="default-64-event-build"),
                                   pytest.param((False, ("-DSVM_MAX_EVENTS=100",)), id="wide-100-event-build")])
def test_a_model_of_20_events_runs_as_the_reference(tmp_path, build):
    """No corpus model has 17 to 24 events, and the quick host tests build each with its exact
    limits only: a mask of 3 bytes in a 4-byte integer (a bit loaded past the last byte fired a
    phantom event), the valid-event mask of an image narrower than the build (mask_low past its
    first whole byte) and the masks kept as byte arrays (over 64 events: the loops over their
    bytes, the cursor's byte index) went unchecked."""
    exact_limits, defines = build
    b = batch(twenty_event_model(tmp_path))
    exe = c_harness.build_host(b, tmp_path / "build", exact_limits=exact_limits, defines=defines)
    traces, info = c_harness.parse(c_harness.run_host(exe))
    assert mismatches(b, traces, info, passes=(0, 1)) == []


def with_pad_bit(image: bytes, mask: str) -> bytes:
    """``image`` with the lowest bit past its events set in its controllable or public mask, resealed."""
    body = bytearray(image[:-F.CRC_SIZE])
    events, width = body[F.OFFSETS["num_events"]], body[F.OFFSETS["mask_bytes"]]
    at = F.HEADER_SIZE + (width if mask == "public" else 0) + events // 8
    body[at] |= 1 << events % 8
    return bytes(body) + F.crc16(bytes(body)).to_bytes(F.CRC_SIZE, "little")


def test_a_mask_bit_past_the_events_is_refused_whatever_the_number_of_events(tmp_path):
    """The check of the bits past the last event (beyond_events) for 2, 5 and 10 events: the
    reader parity tests set such a bit in an image of 10 events only, which other checks refuse
    too. The unedited images load."""
    images = [batch(p).image for p in SUPERVISORS if p.rsplit("/", 1)[-1] in
              ("public_example.yaml", "flipflop_S.yaml", "energy_worker.yaml")]
    cases = [(image, F.ErrorCode.OK) for image in images] + \
        [(with_pad_bit(image, mask), F.ErrorCode.LAYOUT) for image in images for mask in ("controllable", "public")]
    body = "\n".join(c_array("image_%d" % k, image) for k, (image, _) in enumerate(cases))
    body += "\n" + "\n".join("    printf(\"%%d\\n\", svm_validate(image_%d, %d, SVM_SOURCE_RAM));" % (k, len(image))
                             for k, (image, _) in enumerate(cases))
    assert run_c(tmp_path, body) == [str(int(code)) for _, code in cases]


def with_target(image: bytes, value: int) -> bytes:
    """``image`` (one-byte state numbers) with its first transition's target set to ``value``, resealed."""
    parsed = F.Image.parse(image)
    m, n, s = (parsed.num_events + 7) // 8, parsed.num_supervisors, len(parsed.state_defined)
    body = bytearray(image[:-F.CRC_SIZE])
    body[F.HEADER_SIZE + 2 * m + n * (m + 6) + s * (m + 2)] = value
    return bytes(body) + F.crc16(bytes(body)).to_bytes(F.CRC_SIZE, "little")


def test_a_target_one_past_its_supervisors_last_state_is_refused(tmp_path):
    """The first supervisor of flipflop_S has 2 states: target 1 loads, target 2 (one past) is
    refused; the reader tests had only targets far past the end (0xFF, a state count of 8)."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/flipflop_S.yaml"))).image
    assert F.Image.parse(image).sup_num_states[0] == 2
    cases = [with_target(image, 1), with_target(image, 2)]
    body = "\n".join(c_array("image_%d" % k, raw) for k, raw in enumerate(cases))
    body += "\n" + "\n".join("    printf(\"%%d\\n\", svm_validate(image_%d, %d, SVM_SOURCE_RAM));" % (k, len(raw))
                             for k, raw in enumerate(cases))
    assert run_c(tmp_path, body) == [str(int(F.ErrorCode.OK)), str(int(F.ErrorCode.LAYOUT))]


def test_a_check_alone_moves_by_name_and_an_unbound_event_may_lose_its_name(tmp_path):
    """On a swap, a binding made of a check alone (no action, no data) is a binding, carried to
    its event's new index; an event bound to nothing needs no name in the new image. The API
    check binds actions with data only, and every event it leaves unbound keeps its name."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))).image
    parsed = F.Image.parse(image)
    names, events = parsed.names, parsed.num_events
    checked = next(e for e in range(1, events) if not parsed.controllable >> e & 1)
    rotated, missing = _with_names(image, names[1:] + names[:1]), _with_names(image, ["zz" + names[0]] + names[1:])
    body = "\n".join([c_array("image", image), c_array("rotated", rotated), c_array("missing", missing), """
    static svm_vm_t vm;
    static svm_binding_t table[SVM_MAX_EVENTS];
    uint8_t e;
    svm_init(&vm);
    printf("%%d\\n", svm_load(&vm, image, sizeof image));
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    printf("%%d\\n", svm_bind(&vm, %d, 0, never_occurs, 0));
    printf("%%d\\n", svm_load(&vm, rotated, sizeof rotated));
    for (e = 0; e < SVM_MAX_EVENTS; e++) {
        if (table[e].check != 0) {
            printf("%%u\\n", e);
        }
    }
    printf("%%d\\n", svm_load(&vm, image, sizeof image));
    printf("%%d\\n", svm_load(&vm, missing, sizeof missing));""" % checked])
    printed = run_c(tmp_path, body, defines=("-DSVM_MAX_EVENTS=%d" % events,),
                    prelude="static unsigned char never_occurs(void *data)\n{\n    (void)data;\n    return 0;\n}\n")
    assert printed == ["0", "0", "0", str(checked - 1), "0", "0"]


def test_bindings_swapped_in_pairs_each_land_on_their_partner(tmp_path):
    """Names swapped two by two (0 and 1, ..., 8 and 9) make five cycles of two moves, the last
    among events 8 and 9: the set of moved events must keep events 8 to 15 apart from 0 to 7.
    The API check rotates the names, one cycle, every binding moved in its first pass."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))).image
    names = F.Image.parse(image).names
    events = len(names)
    assert events == 10
    paired = _with_names(image, [names[k ^ 1] for k in range(events)])
    body = "\n".join([c_array("image", image), c_array("paired", paired), """
    static svm_vm_t vm;
    static svm_binding_t table[SVM_MAX_EVENTS];
    static uint8_t tags[SVM_MAX_EVENTS];
    uint8_t e;
    svm_init(&vm);
    printf("%d\\n", svm_load(&vm, image, sizeof image));
    svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
    for (e = 0; e < SVM_MAX_EVENTS; e++) {
        tags[e] = e;
        (void)svm_bind(&vm, e, fired, 0, &tags[e]);
    }
    printf("%d\\n", svm_load(&vm, paired, sizeof paired));
    for (e = 0; e < SVM_MAX_EVENTS; e++) {
        printf("%d\\n", table[e].data == 0 ? -1 : *(uint8_t *)table[e].data);
    }"""])
    printed = run_c(tmp_path, body, defines=("-DSVM_MAX_EVENTS=%d" % events,),
                    prelude="static void fired(void *data)\n{\n    (void)data;\n}\n")
    assert printed == ["0", "0"] + [str(k ^ 1) for k in range(events)]


def test_the_dispatch_is_asked_about_the_images_events_only(tmp_path):
    """A build for 64 events running an image of 10: the step polls the image's uncontrollable
    events only (valid_events), never an index the image does not have."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))).image
    body = "\n".join([c_array("image", image), """
    static svm_vm_t vm;
    unsigned k;
    svm_init(&vm);
    printf("%d\\n", svm_load(&vm, image, sizeof image));
    svm_set_dispatch(&vm, dispatch);
    for (k = 0; k < 20u; k++) {
        (void)svm_step(&vm);
    }
    printf("%d %d\\n", asked, highest);"""])
    printed = run_c(tmp_path, body, prelude="static int asked, highest = -1;\n\n"
                    "static uint8_t dispatch(svm_vm_t *vm, uint8_t event, uint8_t op)\n{\n    (void)vm;\n"
                    "    if (op == SVM_OP_CHECK) {\n        asked++;\n"
                    "        highest = event > highest ? event : highest;\n    }\n    return (uint8_t)(event % 3u == 0u);\n}\n")
    parsed = F.Image.parse(image)
    uncontrollable = [e for e in range(parsed.num_events) if not parsed.controllable >> e & 1]
    assert printed == ["0", str(20 * len(uncontrollable)), str(uncontrollable[-1])]


def test_a_vm_without_an_image_steps_and_enables_nothing(tmp_path):
    """svm_init without svm_load (or after a refused one): no event enabled, none fired."""
    body = """    static svm_vm_t vm;
    uint8_t enabled[SVM_MASK_BYTES] = {0};
    svm_init(&vm);
    printf("%u %u %u\\n", svm_enabled(&vm, enabled), svm_step(&vm), enabled[0]);"""
    assert run_c(tmp_path, body) == ["0", "0", "0"]


def tiny_weights_model(tmp_path: Path) -> str:
    """Two supervisors whose controllable events a and b have weights of a few Q15 units in some
    states (a weighted draw then lands on a boundary, pick == weight, one time in three) and
    other weights in their other state."""
    path = tmp_path / "tiny_weights.yaml"
    path.write_text(supervisor_yaml(
        ["a", "b", "u"], [1, 1, 0], [{"a", "b", "u"}, {"a", "u"}],
        [[[("a", 1), ("b", 0), ("u", 1)], [("a", 0), ("b", 1), ("u", 0)]],
         [[("a", 1), ("u", 0)], [("a", 0), ("u", 1)]]],
        probabilities=[[["0.00003", "0.00006"], ["0.25", "0.75"]], [["0.5"], ["0.00009"]]]))
    return str(path)


def test_weighted_draws_on_tiny_weights_in_every_state_run_as_the_reference(tmp_path):
    """The corpus's weights are large (a draw on a boundary is rare) and its weighted model has one
    supervisor: the boundary of the weighted draw (pick < w) and the weight read in a state other
    than the supervisor's first went unchecked."""
    b = batch(tiny_weights_model(tmp_path))
    exe = c_harness.build_host(b, tmp_path / "build")
    traces, info = c_harness.parse(c_harness.run_host(exe))
    assert mismatches(b, traces, info, passes=(0, 1)) == []


def test_the_nth_event_of_a_byte_mask(tmp_path):
    """svm_mask_nth (the public helper a learned chooser uses to turn a draw into an event) for
    each n over masks with bits in the first and later bytes, and past the last event."""
    masks = [bytes([0x01, 0x00]), bytes([0x81, 0x00]), bytes([0x00, 0x06]), bytes([0xF0, 0x0F]), bytes([0xFF, 0xFF])]
    body = "\n".join(c_array("mask_%d" % k, mask) for k, mask in enumerate(masks)) + "\n    uint8_t n;\n"
    body += "\n".join("    for (n = 0; n <= 16u; n++) {\n        printf(\"%%u\\n\", svm_mask_nth(mask_%d, 2, n));\n"
                      "    }" % k for k in range(len(masks)))
    expected = []
    for mask in masks:
        events = [e for e in range(16) if mask[e >> 3] >> (e & 7) & 1]
        expected += [str(events[n]) if n < len(events) else "255" for n in range(17)]
    assert run_c(tmp_path, body) == expected


def test_names_looked_up_and_read_back(tmp_path):
    """svm_event_index, svm_event_index_n, svm_has_names and svm_event_name at their edges: a
    name's prefix is no name, an image without names has none, the event one past the last has no
    name, a buffer of one byte gets the empty string even for an event out of range; a name given
    with its length needs no NUL (the byte after it is not read as part of it), and its "EV_" is
    not taken off."""
    path = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))
    image, bare = batch(path).image, compile_inputs([path], names=False).image
    names = F.Image.parse(image).names
    events = len(names)
    body = "\n".join([c_array("image", image), c_array("bare", bare), """
    static svm_vm_t vm;
    char buf[8];
    unsigned len;
    svm_init(&vm);
    printf("%%u\\n", svm_has_names(&vm));
    printf("%%d\\n", svm_load(&vm, bare, sizeof bare));
    printf("%%u\\n", svm_has_names(&vm));
    printf("%%d\\n", svm_load(&vm, image, sizeof image));
    printf("%%u\\n", svm_has_names(&vm));
    printf("%%d %%d %%d\\n", svm_event_index(&vm, "EV_%s"), svm_event_index(&vm, "%s"), svm_event_index(&vm, "%s"));
    printf("%%d %%d %%d\\n", svm_event_index_n(&vm, "%sx", %d), svm_event_index_n(&vm, "%s", %d),
           svm_event_index_n(&vm, "EV_%s", %d));
    buf[0] = 'x';
    len = svm_event_name(&vm, %d, buf, 1);
    printf("%%u %%u\\n", len, (unsigned)buf[0]);
    buf[0] = 'x';
    len = svm_event_name(&vm, 0, buf, 1);
    printf("%%u %%u\\n", len, (unsigned)buf[0]);
    len = svm_event_name(&vm, %d, buf, sizeof buf);
    printf("%%u %%s\\n", len, buf);""" % (
        names[0], names[0][:-1], names[0] + "x",
        names[1], len(names[1]), names[1], len(names[1]) - 1, names[1], len(names[1]) + 3, events, events - 1)])
    last = names[-1]
    assert run_c(tmp_path, body) == ["0", "0", "0", "0", "1", "0", "-1", "-1", "1", "-1", "-1", "0", "0",
                                     str(len(names[0])), "0",
                                     str(len(last)), last[:7]]


def test_inspection_answers_nothing_out_of_range(tmp_path):
    """The inspection functions without an image and for supervisors past the last (after an
    image with more supervisors ran: its states are still in the VM), and svm_is_public /
    svm_is_controllable for every event and one past the last (the API check reads neither),
    also in an image of 8 events, where the byte past the masks is the next section's."""
    image = batch(next(p for p in SUPERVISORS if p.endswith("/hitl_leader.yaml"))).image
    bigger = batch(next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))).image
    parsed = F.Image.parse(image)
    n, events = parsed.num_supervisors, parsed.num_events
    assert F.Image.parse(bigger).num_supervisors > n + 1 and parsed.public
    eight = batch(next(p for p in SUPERVISORS if p.endswith("/network_leader.yaml"))).image     # event 8: byte 1
    body = "\n".join([c_array("image", image), c_array("bigger", bigger), c_array("eight", eight), """
    static svm_vm_t vm;
    uint8_t k;
    svm_init(&vm);
    printf("%%u %%u %%u\\n", svm_first_state(&vm, 0), svm_state(&vm, 0), svm_global_state(&vm, 0));
    printf("%%d\\n", svm_load(&vm, bigger, sizeof bigger));
    for (k = 0; k < 30u; k++) {
        (void)svm_step(&vm);
    }
    printf("%%d\\n", svm_load(&vm, image, sizeof image));
    for (k = %d; k <= %d; k++) {
        printf("%%u %%u %%u\\n", svm_first_state(&vm, k), svm_state(&vm, k), svm_global_state(&vm, k));
    }
    for (k = 0; k <= %d; k++) {
        printf("%%u%%u\\n", svm_is_public(&vm, k), svm_is_controllable(&vm, k));
    }
    printf("%%d\\n", svm_load(&vm, eight, sizeof eight));
    printf("%%u%%u\\n", svm_is_public(&vm, 8), svm_is_controllable(&vm, 8));""" % (n, n + 1, events)])
    flags = ["%d%d" % (parsed.public >> e & 1, parsed.controllable >> e & 1) for e in range(events)] + ["00"]
    assert run_c(tmp_path, body) == ["0"] * 11 + flags + ["0", "00"]


def test_a_model_with_two_byte_state_numbers_runs_as_the_reference(tmp_path):
    """No corpus model has over 256 states, so none has two-byte targets, which the readers'
    tests only load: energy_worker rewritten with state_width 2 steps as the reference does."""
    b = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    wide = dataclasses.replace(b, image=_edited(b.image, _set(state_width=2)))
    assert wide.image[F.OFFSETS["state_width"]] == 2
    exe = c_harness.build_host(wide, tmp_path / "build")
    traces, info = c_harness.parse(c_harness.run_host(exe))
    assert mismatches(wide, traces, info, passes=(0, 1)) == []
