"""Write the C and C++ runtimes' copies of the image format's numbers from its one definition.

The C runtime's host-build checksum tables (runtime_c/swarmvm_crc_tables.h) are written here
too, from the format's crc16.

A microcontroller cannot import runtime_py/swarmvm_format.py, so the C runtime reads the format's
version, magic, header size and field offsets, flags, limits, Q15 one, checksum seed, stream
chunk size and result codes from runtime_c/swarmvm_format.h, and the C++ runtime from
runtime_cpp/swarmvm_format.hpp. Both are written here, from the module itself, and committed;
tests/compiler/test_format_headers.py writes them again in memory and fails when a committed copy
differs, as the golden copies do (``make format-headers`` rewrites them after a change of the
format).

    python scripts/format_headers.py            # rewrite both headers
    python scripts/format_headers.py --check    # exit 1, naming the stale ones, if they differ
"""

import argparse
import inspect
import re
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parent.parent
C_HEADER = ROOT / "runtime_c" / "swarmvm_format.h"
CPP_HEADER = ROOT / "runtime_cpp" / "swarmvm_format.hpp"
REGENERATE = "make format-headers (python scripts/format_headers.py)"


def format_module() -> ModuleType:
    """runtime_py/swarmvm_format.py, imported from this checkout (standard library only)."""
    sys.path.insert(0, str(ROOT))
    try:
        from runtime_py import swarmvm_format
    finally:
        sys.path.remove(str(ROOT))
    return swarmvm_format


def code_comments(f: ModuleType) -> dict[str, str]:
    """Each ErrorCode's comment in swarmvm_format.py (a comment continued on the lines under
    its code joined into one), so both headers say what a code means in the definition's words."""
    comments: dict[str, str] = {}
    name = None
    for line in inspect.getsource(f.ErrorCode).splitlines():
        member = re.match(r"\s+([A-Z_]+) = \d+\s*(?:# (.*))?$", line)
        more = re.match(r"\s+# (.*)$", line)
        if member:
            name = member.group(1)
            comments[name] = member.group(2) or ""
        elif more and name is not None:
            comments[name] += " " + more.group(1)
    return comments


def numbers(f: ModuleType) -> list[tuple[str, int, str, str]]:
    """(name as swarmvm_format spells it, value, C++ type, comment) of every number both
    runtimes take from the format, in the order the headers list them."""
    rows = [("FORMAT_VERSION", f.FORMAT_VERSION, "std::uint8_t", ""),
            ("MAGIC", int.from_bytes(f.MAGIC, "little"), "std::uint32_t", '"%s", as a little-endian u32' % f.MAGIC.decode()),
            ("HEADER_SIZE", f.HEADER_SIZE, "std::size_t", ""),
            ("CRC_SIZE", f.CRC_SIZE, "std::size_t", ""),
            ("MIN_IMAGE_SIZE", f.MIN_IMAGE_SIZE, "std::size_t", "header and checksum"),
            ("MAX_IMAGE_SIZE", f.MAX_IMAGE_SIZE, "std::size_t", "the length field is a u16")]
    rows += [("AT_" + field.upper(), offset, "std::size_t", "offset of the header's %s" % field)
             for field, offset in f.OFFSETS.items()]
    rows += [(name, getattr(f, name), "std::uint8_t", comment) for name, comment in (
        ("FLAG_NAMES", "the names section is present"),
        ("FLAG_PROBS", "the probability section is present"),
        ("FLAG_ORDER", "the order section (source-file event indices) is present"),
        ("FLAG_SOURCE", "the source section (the compatibility layers': skipped) is present"),
        ("KNOWN_FLAGS", "an image with any other flag bit is refused"))]
    rows += [("MAX_EVENTS", f.MAX_EVENTS, "unsigned", "the format's limits: a build's SVM_MAX_* stay within them"),
             ("MAX_SUPERVISORS", f.MAX_SUPERVISORS, "unsigned", ""),
             ("MAX_STATES", f.MAX_STATES, "unsigned", ""),
             ("Q15_ONE", f.Q15_ONE, "std::uint32_t", "probability 1 in the probability section's Q15"),
             ("CRC16_INIT", f.crc16(b""), "std::uint16_t", "the checksum's start (CRC-16/MCRF4XX)"),
             ("STREAM_CHUNK_DATA", f.STREAM_CHUNK_DATA, "std::size_t", "image bytes in a stream chunk")]
    return rows


def c_name(name: str) -> str:
    """swarmvm.h's spelling: SVM_<NAME>, the limits as SVM_FORMAT_MAX_* (SVM_MAX_* are a build's)."""
    return "SVM_FORMAT_" + name if name.startswith("MAX_") and name != "MAX_IMAGE_SIZE" else "SVM_" + name


def cpp_name(name: str) -> str:
    """swarmvm.hpp's spelling: k<Name> in camel case."""
    return "k" + "".join(part.capitalize() for part in name.lower().split("_"))


def c_literal(value: int) -> str:
    """An unsigned C literal of ``value``: a long in hex past 16 bits (the magic)."""
    return "0x%XUL" % value if value > 0xFFFF else "%du" % value


def _banner(comment: str) -> list[str]:
    return [comment + " Generated from runtime_py/swarmvm_format.py by scripts/format_headers.py: do not edit.",
            comment + " After a change of the format run `make format-headers`: tests/compiler/test_format_headers.py",
            comment + " fails while this copy differs from what the script writes."]


def c_header(f: ModuleType) -> str:
    """runtime_c/swarmvm_format.h: the numbers as macros, the result codes as ``enum svm_result``."""
    lines = ["/* swarmvm table image format (docs/image-format.md), for the C runtime (swarmvm.h includes it)."]
    lines += [" *" + text[2:] for text in _banner("//")] + [" */", "#ifndef SWARMVM_FORMAT_H", "#define SWARMVM_FORMAT_H", ""]
    for name, value, _, comment in numbers(f):
        define = "#define %s %s" % (c_name(name), c_literal(value))
        lines.append(define if not comment else "%-40s/* %s */" % (define, comment))
    comments = code_comments(f)
    codes = list(f.ErrorCode)
    lines += ["", "/* Result codes of svm_load and friends (0 = success): swarmvm_format.ErrorCode. */", "enum svm_result {"]
    for i, code in enumerate(codes):
        entry = "    %s = %d%s" % ("SVM_OK" if code == 0 else "SVM_ERR_" + code.name, int(code), "," if i + 1 < len(codes) else "")
        lines.append(entry if not comments[code.name] else "%-30s/* %s */" % (entry, comments[code.name]))
    return "\n".join(lines + ["};", "", "#endif", ""])


def cpp_header(f: ModuleType) -> str:
    """runtime_cpp/swarmvm_format.hpp: the numbers as constexpr, the image codes as ErrorCode."""
    lines = ["// swarmvm table image format (docs/image-format.md), for the C++ runtime (swarmvm_vm.hpp includes it)."]
    lines += _banner("//") + ["#ifndef SWARMVM_FORMAT_HPP", "#define SWARMVM_FORMAT_HPP", "",
                              "#include <cstddef>", "#include <cstdint>", "", "namespace swarmvm {", ""]
    for name, value, kind, comment in numbers(f):
        define = "constexpr %s %s = %s;" % (kind, cpp_name(name), ("0x%Xu" % value) if value > 0xFFFF else value)
        lines.append(define if not comment else "%-52s// %s" % (define, comment))
    comments = code_comments(f)
    codes = [code for code in f.ErrorCode if f.ErrorCode.LENGTH <= code <= f.ErrorCode.LAYOUT]
    lines += ["", "// Why a reader refuses an image: the numbers of swarmvm.h's SVM_ERR_* (swarmvm_format.ErrorCode),",
              "// so every runtime gives the same code for the same bad image.", "enum class ErrorCode : int {"]
    for i, code in enumerate(codes):
        entry = "    %s = %d%s" % (code.name.lower(), int(code), "," if i + 1 < len(codes) else "")
        lines.append("%-18s// %s" % (entry, comments[code.name]))
    return "\n".join(lines + ["};", "", "}  // namespace swarmvm", "", "#endif", ""])


def crc_tables_header(f: ModuleType) -> str:
    """runtime_c/swarmvm_crc_tables.h: the host build's checksum tables (swarmvm.c with
    SVM_CRC_TABLE, four bytes a step), each entry the format's own crc16 from 0 of byte x and
    then none, one, two or three zero bytes; a microcontroller build never includes them."""
    lines = ["/* The CRC-16/MCRF4XX tables of the C runtime's host build (swarmvm.c includes them with",
             " * SVM_CRC_TABLE, off on microcontrollers): T[x] is the sum from 0 after byte x, and T2, T3, T4",
             " * after byte x and then one, two, three zero bytes, so that a step takes two or four bytes."]
    lines += [" *" + text[2:] for text in _banner("//")] + [" */", "#ifndef SWARMVM_CRC_TABLES_H",
                                                            "#define SWARMVM_CRC_TABLES_H", "", "#include <stdint.h>"]
    for zeros, name in enumerate(("crc_table", "crc_table2", "crc_table3", "crc_table4")):
        values = [f.crc16(bytes([x] + [0] * zeros), 0) for x in range(256)]
        lines += ["", "static const uint16_t %s[256] = {" % name]
        rows = [", ".join("0x%04X" % v for v in values[i:i + 8]) for i in range(0, 256, 8)]
        lines += ["    " + row + ("," if i + 1 < len(rows) else "") for i, row in enumerate(rows)] + ["};"]
    return "\n".join(lines + ["", "#endif", ""])


HEADERS = ((C_HEADER, c_header), (CPP_HEADER, cpp_header), (ROOT / "runtime_c" / "swarmvm_crc_tables.h", crc_tables_header))


def stale(f: ModuleType) -> list[Path]:
    """The committed headers that differ from what this script writes."""
    return [path for path, write in HEADERS if not path.is_file() or path.read_text() != write(f)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="only compare: exit 1 if a committed header differs")
    args = parser.parse_args(argv)
    f = format_module()
    if args.check:
        for path in stale(f):
            print("%s differs from swarmvm_format.py: run %s" % (path.relative_to(ROOT), REGENERATE), file=sys.stderr)
        return 1 if stale(f) else 0
    for path, write in HEADERS:
        path.write_text(write(f))
        print("wrote %s" % path.relative_to(ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
