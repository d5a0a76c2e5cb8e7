"""Build and run the C learning probes (host gcc, avr-gcc + simavr) for the learning tests."""

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RUNTIME_C = ROOT / "runtime_c"
PROBES = Path(__file__).resolve().parent / "c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
# Kilobot flags (the optimisation level is chosen per build) plus dead-code removal, without
# which -O3 builds of the core and the learning code overflow the 32 KB part.
AVR_FLAGS = ["-mmcu=atmega328p", "-DF_CPU=8000000", "-funsigned-char", "-funsigned-bitfields", "-fpack-struct",
             "-fshort-enums", "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections"]


def c_double(value):
    return repr(float(value))


def write_stream_header(path, stream, grid):
    """probe_data.h: the labelled stream (distance, mass, soc, label) and the grid size."""
    lines = ["#define PROBE_STREAM %d" % len(stream), "#define PROBE_GRID %d" % grid,
             "static const svl_real probe_stream[%d][4] PROBE_CONST = {" % max(1, len(stream))]
    lines += ["    {%s, %s, %s, %d}," % (c_double(x[0]), c_double(x[1]), c_double(x[2]), y) for x, y in stream]
    lines.append("};")
    Path(path).write_text("\n".join(lines) + "\n")


def _compile(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError("compile failed: %s\n%s" % (" ".join(cmd), done.stderr))


def build_host(out, sources, includes=(), defines=()):
    cmd = ["gcc", *STRICT, "-O2", *["-I%s" % i for i in (RUNTIME_C, PROBES, *includes)],
           *["-D%s" % d for d in defines], *map(str, sources), "-o", str(out), "-lm"]
    _compile(cmd)
    return out


def build_avr(out, sources, includes=(), defines=(), optimise="-Os"):
    cmd = ["avr-gcc", *AVR_FLAGS, optimise, *STRICT, *["-I%s" % i for i in (RUNTIME_C, PROBES, *includes)],
           *["-D%s" % d for d in defines], *map(str, sources), "-o", str(out), "-lm"]
    _compile(cmd)
    return out


def run_host(exe, timeout=60):
    return subprocess.run([str(exe)], check=True, capture_output=True, text=True, timeout=timeout).stdout


def run_simavr(elf, timeout=300):
    """The USART0 text of an AVR run. simavr prints it on stderr, coloured, each newline shown
    as '.' and long lines cut every 256 characters; probes print no '.' of their own, so the
    text is rebuilt by dropping simavr's line breaks and turning '.' back into newlines."""
    done = subprocess.run(["simavr", "-m", "atmega328p", "-f", "8000000", str(elf)],
                          capture_output=True, text=True, timeout=timeout)
    text = re.sub(r"\x1b\[[0-9;]*m", "", done.stderr)
    return text.replace("\n", "").replace(".", "\n")


def parse_lines(text, tags):
    """{tag: payload} for probe lines 'TAG payload'; works on stdout and on simavr's stream."""
    found = {}
    for tag in tags:
        match = re.search(r"(?:^|[\n.])%s ([0-9a-f ]+)" % re.escape(tag), text)
        if match:
            found[tag] = match.group(1).strip()
    return found
