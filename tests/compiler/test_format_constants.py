"""The C and C++ runtimes' format constants equal the one definition, as their compilers see them.

A microcontroller cannot import runtime_py/swarmvm_format.py, so swarmvm.h (with
swarmvm_stream.h) and swarmvm.hpp keep their own copies. Rather than reading those copies with
regular expressions (which miss a value spelled another way, an ``#if`` around it or a second
definition), each test here compiles a small program that includes the header and prints every
constant as the compiler evaluated it, then compares the printout with the Python definition:
version, magic, header size and each field's offset, flags, limits, result codes, stream chunk
sizes, the Q15 one, the seeds and the violation counter's stop. The Q15 one and the seed that
replaces 0 are also read from what the VM does with them (swarmvm.c uses the header's)."""

import subprocess

from checkout import EXAMPLE
from swarmvm.targets import kilobot
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_C, RUNTIME_CPP, image_format, python_vm

F = image_format()
VM = python_vm()
WARNINGS = ["-Wall", "-Wextra", "-Werror", "-pedantic"]


def _image_constants():
    """{NAME: value}, C's spelling without SVM_: what both headers define about the image."""
    values = {"FORMAT_VERSION": F.FORMAT_VERSION, "MAGIC": int.from_bytes(F.MAGIC, "little"),
              "HEADER_SIZE": F.HEADER_SIZE, "CRC_SIZE": F.CRC_SIZE, "MIN_IMAGE_SIZE": F.MIN_IMAGE_SIZE,
              "FLAG_NAMES": F.FLAG_NAMES, "FLAG_PROBS": F.FLAG_PROBS, "FLAG_ORDER": F.FLAG_ORDER,
              "FLAG_SOURCE": F.FLAG_SOURCE, "KNOWN_FLAGS": F.KNOWN_FLAGS}
    values.update({"AT_" + field.upper(): offset for field, offset in F.OFFSETS.items()})
    return values


def c_expected():
    """{C expression: value} of everything swarmvm.h and swarmvm_stream.h define about the format."""
    values = {"SVM_" + name: value for name, value in _image_constants().items()}
    values.update({"SVM_FORMAT_MAX_EVENTS": F.MAX_EVENTS, "SVM_FORMAT_MAX_SUPERVISORS": F.MAX_SUPERVISORS,
                   "SVM_FORMAT_MAX_STATES": F.MAX_STATES, "SVM_MAX_VIOLATIONS": VM.MAX_VIOLATIONS,
                   "SVM_DEFAULT_SEED": VM.XorShift32().state, "SVM_ZERO_SEED": VM.XorShift32(0).state,
                   "SVM_Q15_ONE": F.Q15_ONE, "SVM_CRC16_INIT": F.crc16(b""),
                   "SVM_CHUNK_DATA": F.STREAM_CHUNK_DATA, "SVM_CHUNK_BYTES": 1 + F.STREAM_CHUNK_DATA})
    values.update({"SVM_OK" if code == 0 else "SVM_ERR_" + code.name: int(code) for code in F.ErrorCode})
    # What the VM does with them: every event weighs one in an image without probabilities, and
    # seed 0 starts the generator from the replacing seed (its first draw is compared).
    values["svm_weight(&vm, 0)"] = F.Q15_ONE
    values["first_draw_of_seed_0(&vm)"] = VM.XorShift32(0).next()
    return values


def cpp_expected():
    """{C++ expression: value} of everything swarmvm.hpp defines about the format."""
    values = {"swarmvm::k" + "".join(part.capitalize() for part in name.lower().split("_")): value
              for name, value in _image_constants().items()}
    values.update({"swarmvm::kMaxImageSize": F.MAX_IMAGE_SIZE, "swarmvm::kQ15One": F.Q15_ONE,
                   "swarmvm::kZeroSeed": VM.XorShift32(0).state, "swarmvm::kMaxViolations": VM.MAX_VIOLATIONS})
    # The C++ reader raises the image codes (LENGTH .. LAYOUT); it has no build limits or C API.
    values.update({"swarmvm::ErrorCode::" + code.name.lower(): int(code) for code in F.ErrorCode
                   if F.ErrorCode.LENGTH <= code <= F.ErrorCode.LAYOUT})
    return values


def _printer(expressions, cast):
    """C/C++ statements printing each expression as ``expression value``, one a line."""
    return "".join('    printf("%%s %%llu\\n", "%s", (unsigned long long)%s(%s));\n' % (e, cast, e) for e in expressions)


def _run(tmp_path, command, source, name):
    program = tmp_path / name
    (tmp_path / (name + source[0])).write_text(source[1])
    subprocess.run([*command, str(tmp_path / (name + source[0])), "-o", str(program)], check=True)
    lines = subprocess.run([str(program)], check=True, capture_output=True, text=True).stdout.splitlines()
    return {expression: int(value) for expression, value in (line.rsplit(" ", 1) for line in lines)}


def test_c_constants_as_compiled_equal_the_definition(tmp_path):
    image = compile_inputs([str(EXAMPLE)]).image
    assert not F.Image.parse(image).probs        # so that every weight is one
    source = """#include <stdio.h>
#include "swarmvm.h"
#include "swarmvm_stream.h"

static const uint8_t image[] = {%s};

static uint32_t first_draw_of_seed_0(svm_vm_t *vm)
{
    svm_set_options(vm, 0, 0);
    svm_reset(vm);
    return svm_random(vm);
}

int main(void)
{
    static svm_vm_t vm;
    svm_init(&vm);
    if (svm_load(&vm, image, sizeof image) != SVM_OK) {
        return 1;
    }
%s    return 0;
}
""" % (", ".join(map(str, image)), _printer(c_expected(), ""))
    command = ["gcc", "-std=c99", *WARNINGS, "-I", str(RUNTIME_C), str(RUNTIME_C / "swarmvm.c")]
    assert _run(tmp_path, command, (".c", source), "c_constants") == c_expected()


def test_cpp_constants_as_compiled_equal_the_definition(tmp_path):
    source = """#include <cstdio>
#include "swarmvm.hpp"

int main()
{
%s    return 0;
}
""" % _printer(cpp_expected(), "static_cast<unsigned long long>").replace("(unsigned long long)", "")
    command = ["g++", "-std=c++17", *WARNINGS, "-I", str(RUNTIME_CPP)]
    assert _run(tmp_path, command, (".cpp", source), "cpp_constants") == cpp_expected()


def test_a_stream_chunk_is_one_kilobot_message():
    """The chunk (sequence byte and image bytes) fills a kilolib message's payload exactly."""
    assert 1 + F.STREAM_CHUNK_DATA == kilobot.KILOBOT_MESSAGE_BYTES


def test_header_offsets_follow_the_documented_table():
    assert F.OFFSETS == {"magic": 0, "version": 4, "flags": 5, "num_events": 6, "num_supervisors": 7,
                         "num_states": 8, "num_transitions": 10, "state_width": 12, "mask_bytes": 13,
                         "length": 14}
    assert F.HEADER_SIZE == 16 and F.MIN_IMAGE_SIZE == 18
