"""The C and C++ runtimes' image-format constants equal the one definition (swarmvm_format.py).

A microcontroller cannot import the Python definition, so swarmvm.h and swarmvm.hpp keep their
own copies; this test reads them from the sources and compares every one: version, magic,
header size and every field's offset, flag bits, size limits and the result codes."""

import re

from swarmvm.runtime import RUNTIME_C, RUNTIME_CPP, image_format

F = image_format()
C_HEADER = (RUNTIME_C / "swarmvm.h").read_text()
CPP_HEADER = (RUNTIME_CPP / "swarmvm.hpp").read_text()


def _c_defines():
    return {name: int(value, 0) for name, value in
            re.findall(r"^#define SVM_(\w+) (0x[0-9A-Fa-f]+|\d+)U?L?\b", C_HEADER, re.M | re.I)}


def _cpp_constants():
    return {name: int(value, 0) for name, value in
            re.findall(r"^constexpr std::\w+ k(\w+) = (0x[0-9A-Fa-f]+|\d+)u?;", CPP_HEADER, re.M)}


def _camel(snake):
    return "".join(part.capitalize() for part in snake.split("_"))


def _expected():
    """{NAME: value} in the C spelling (SVM_ prefix dropped)."""
    values = {"FORMAT_VERSION": F.FORMAT_VERSION, "MAGIC": int.from_bytes(F.MAGIC, "little"),
              "HEADER_SIZE": F.HEADER_SIZE, "CRC_SIZE": F.CRC_SIZE, "MIN_IMAGE_SIZE": F.MIN_IMAGE_SIZE,
              "FLAG_NAMES": F.FLAG_NAMES, "FLAG_PROBS": F.FLAG_PROBS, "FLAG_ORDER": F.FLAG_ORDER,
              "KNOWN_FLAGS": F.KNOWN_FLAGS}
    values.update({"AT_" + field.upper(): offset for field, offset in F.OFFSETS.items()})
    return values


def test_header_offsets_follow_the_documented_table():
    assert F.OFFSETS == {"magic": 0, "version": 4, "flags": 5, "num_events": 6, "num_supervisors": 7,
                         "num_states": 8, "num_transitions": 10, "state_width": 12, "mask_bytes": 13,
                         "length": 14}
    assert F.HEADER_SIZE == 16 and F.MIN_IMAGE_SIZE == 18


def test_c_constants_equal_the_definition():
    defines = _c_defines()
    assert {name: defines.get(name) for name in _expected()} == _expected()


def test_cpp_constants_equal_the_definition():
    constants = _cpp_constants()
    expected = {_camel(name.lower()): value for name, value in _expected().items()}
    expected["MaxImageSize"] = F.MAX_IMAGE_SIZE
    assert {name: constants.get(name) for name in expected} == expected


def test_c_result_codes_equal_the_definition():
    body = re.search(r"enum svm_result \{(.*?)\};", C_HEADER, re.S).group(1)
    codes = {name: int(value) for name, value in re.findall(r"SVM_(?:ERR_)?(\w+) = (\d+)", body)}
    assert codes == {code.name: int(code) for code in F.ErrorCode}


def test_cpp_image_error_codes_equal_the_definition():
    """The C++ reader raises the image codes (LENGTH .. LAYOUT); it has no build limits or C API."""
    body = re.search(r"enum class ErrorCode : int \{(.*?)\};", CPP_HEADER, re.S).group(1)
    codes = {name.upper(): int(value) for name, value in re.findall(r"(\w+) = (\d+)", body)}
    image_codes = [F.ErrorCode.LENGTH, F.ErrorCode.MAGIC, F.ErrorCode.VERSION, F.ErrorCode.CRC, F.ErrorCode.LAYOUT]
    assert codes == {code.name: int(code) for code in image_codes}
