"""Conformance of the C VM on the host: every run of every corpus batch, byte for byte.

One harness program per supervisor (firmware/harness/ + runtime_c/, built with gcc under
-std=c99 -Wall -Wextra -Werror -pedantic) replays all 72 runs (inputs x control x policy x
seeds/scripts) twice: pass 0 with the image compiled in and compile-time dispatch, pass 1 with
the image copied to RAM, swapped in with svm_load and runtime bindings (rebound by name).
Each pass must print exactly cases.reference; a corrupted copy must be refused first. Built
with the model's exact limits (the unrolled path for its mask width) and with the default
limits (the generic path)."""

import subprocess
from pathlib import Path

import pytest

from conformance import c_harness
from conformance._c_compare import mismatches
from conformance.cases import SUPERVISORS, batch
from swarmvm.compiler.runtime_files import RUNTIME_C, python_vm


# Exact limits: one mask width, masks in a native integer; default limits (64 events): images
# narrower than the build, 64-bit masks; wide limits (100 events): masks as byte arrays.
BUILD_LIMITS = {"exact-limits": (True, ()), "default-limits": (False, ()),
          "wide-limits": (False, ("-DSVM_MAX_EVENTS=100",))}


# The exact-limits build runs in the quick suite; the other two (same runs, other code paths) are
# marked slow only for their number: 22 more builds.
@pytest.mark.parametrize("limits", [pytest.param(k, marks=() if k == "exact-limits" else pytest.mark.slow)
                                    for k in BUILD_LIMITS])
@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_host_trace_equals_reference(path, limits, tmp_path):
    b = batch(path)
    exact_limits, defines = BUILD_LIMITS[limits]
    exe = c_harness.build_host(b, tmp_path, exact_limits=exact_limits, defines=defines)
    traces, info = c_harness.parse(c_harness.run_host(exe))
    assert mismatches(b, traces, info, passes=(0, 1)) == []


# svm_result codes (swarmvm.h)
OK, LENGTH, MAGIC, VERSION, CRC, LAYOUT, LIMITS, NAMES, EVENT = range(9)


def _reseal(image):
    """Rewrite the length field and CRC of an edited image."""
    vm = python_vm()
    body = bytearray(image[:-2])
    body[14:16] = (len(body) + 2).to_bytes(2, "little")
    return bytes(body) + vm.crc16(bytes(body)).to_bytes(2, "little")


def _with_names(image, names):
    """The image with its names section replaced (structure unchanged, resealed)."""
    parsed = python_vm().Image.parse(image)
    start = len(image) - 2 - sum(1 + len(n) for n in parsed.names)
    section = b"".join(bytes([len(n)]) + n.encode() for n in names)
    return _reseal(image[:start] + section + image[-2:])


def _c_array(name, data):
    return "static const uint8_t %s[] = {%s};" % (name, ", ".join(str(b) for b in data))


def test_c_api_refusals_names_swap_hooks_and_chooser(tmp_path):
    b = batch(next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml")))
    image, parsed = b.image, python_vm().Image.parse(b.image)
    names = parsed.names
    bad = {
        "truncated": (image[:17], LENGTH),
        "length_field": (image[:-3] + image[-2:], LENGTH),
        "magic": (_reseal(b"SVMX" + image[4:]), MAGIC),
        "version": (_reseal(image[:4] + b"\x02" + image[5:]), VERSION),
        "crc": (image[:-1] + bytes([image[-1] ^ 1]), CRC),
        "mask_bytes": (_reseal(image[:13] + b"\x03" + image[14:]), LAYOUT),
        "target_out_of_range": (_reseal(image[:parsed_targets(parsed)] + b"\xff" + image[parsed_targets(parsed) + 1:]),
                                LAYOUT),
        "too_many_events": (None, LIMITS),
    }
    big = batch(next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))).image
    bad["too_many_events"] = (big, LIMITS)
    controllable = next(e for e in range(parsed.num_events) if parsed.controllable >> e & 1)
    choice_image = batch(next(p for p in SUPERVISORS if p.endswith("/probabilistic_example.yaml"))).image
    plain_vm = python_vm().VM(choice_image, policy="first")
    plain, preferred = plain_vm.enabled()[0], plain_vm.enabled()[-1]
    ranked = python_vm().VM(choice_image, policy="first", priority=[plain_vm.image.event_name(preferred)])
    assert ranked.step() == [preferred]        # the reference agrees on what priority means
    lines = ["#define PROBE_NAME \"%s\"" % names[1], "#define CONTROLLABLE_EVENT %d" % controllable,
             "#define PRIORITY_EVENT %d" % preferred,
             _c_array("image_a", image),
             _c_array("image_choice", batch(next(p for p in SUPERVISORS if p.endswith("/probabilistic_example.yaml"))).image),
             _c_array("image_violating", batch(next(p for p in SUPERVISORS if p.endswith("/flipflop_S.yaml"))).image),
             _c_array("image_rotated", _with_names(image, names[1:] + names[:1])),
             _c_array("image_missing", _with_names(image, ["zz" + names[0]] + names[1:]))]
    for k, (what, (data, _)) in enumerate(bad.items()):
        lines.append(_c_array("bad_%d" % k, data))
    lines += ["#define NUM_BAD %d" % len(bad),
              "static const uint8_t *const bad_images[] = {%s};" % ", ".join("bad_%d" % k for k in range(len(bad))),
              "static const uint16_t bad_lengths[] = {%s};" % ", ".join(str(len(d)) for d, _ in bad.values()),
              "static const char *const bad_names[] = {%s};" % ", ".join('"%s"' % n for n in bad)]
    (tmp_path / "api_cases.h").write_text("\n".join(lines) + "\n")
    exe = tmp_path / "api_check"
    subprocess.run(["gcc", *c_harness.WARNINGS, *c_harness.limits(b), "-I", str(tmp_path), "-I", str(RUNTIME_C),
                    str(Path(__file__).with_name("c_api_check.c")), str(RUNTIME_C / "swarmvm.c"), "-o", str(exe)],
                   check=True, capture_output=True, text=True)
    printed = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.splitlines()
    out = dict(line.split(" ", 1) for line in printed if not line.startswith("validate"))
    refused = {line.split()[1]: int(line.split()[2]) for line in printed if line.startswith("validate")}
    assert refused == {what: code for what, (_, code) in bad.items()}
    assert out["load"] == "0" and out["refused_keeps_logic"] == "1"
    assert int(out["index_EV"]) == 1 and int(out["index_bare"]) == 1 and int(out["index_unknown"]) == -1
    assert int(out["bind_unknown_index"]) == EVENT and int(out["check_on_controllable"]) == EVENT
    assert out["swap_rotated"] == "0" and out["rebound_by_name"] == "1"
    assert int(out["swap_missing_name"]) == NAMES and out["missing_keeps_logic"] == "1"
    violations, hook = out["violations"].split(" hook ")
    assert int(violations) > 0 and violations == hook
    assert out["learned_without_chooser"] == "0"
    assert out["learned_choice"].startswith("1 calls ") and int(out["learned_choice"].split()[-1]) >= 1
    assert int(out["first_plain"]) == plain and int(out["first_priority"]) == preferred != plain
    last = parsed.num_events - 1     # old events 0 and 2 are the rotated image's last and 1
    assert out["priority_swap"] == "0 %d 1" % last
    assert out["priority_missing"] == "%d %d 1" % (NAMES, last)


def parsed_targets(parsed):
    """Byte offset of the first target in an image (for corrupting one)."""
    m, n, s = (parsed.num_events + 7) // 8, parsed.num_supervisors, len(parsed.state_defined)
    return 16 + 2 * m + n * (m + 6) + s * (m + 2)
