"""Swapping logic at run time on the Kilobot: a running application (supervisor A) receives
image B over its message channel in 9-byte chunks and switches to it, from B's initial
states, only once the whole image arrived and passed its checksum; bad streams change nothing.
In simavr with the real kilolib, the messages sent over IR by the simavr Kilobot board
(tests/kilobot_stream_demo.py), one chunk per kilolib tick: none is lost at that rate.
Also the Kilobot target's gen-time check that public events' messages are distinct."""

import re
import subprocess

import pytest

from targets.kilobot.needs import kilolib_or_skip
from kilobot_stream_demo import CORPUS, RUNNING, STRICT, SUPERVISOR_A, SUPERVISOR_B, Program, reference, split
from swarmvm.compiler.image import chunks
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.boundary.output import write_outputs
from swarmvm.targets import generate

pytestmark = pytest.mark.emulator   # runs simavr or QEMU

SVM_ERR_CRC, SVM_ERR_NAMES = 4, 7
START = RUNNING     # tick of chunk 0
NORMAL = 0


def image(name):
    return compile_inputs([str(CORPUS / name)]).image


@pytest.fixture(scope="module")
def program(tmp_path_factory):
    kilolib_or_skip()
    return Program(tmp_path_factory.mktemp("kilobot_swap"))


def arrival(result, data, which=0):
    """The kilolib tick in which the board finished sending the message carrying ``data``."""
    return [m.tick for m in result.rx if m.data == data][which]


@pytest.fixture(scope="module")
def image_b():
    return image(SUPERVISOR_B.name)


@pytest.mark.emulator
def test_the_swap_comes_after_the_last_chunk_and_runs_b_from_reset(program, image_b):
    # Every chunk comes twice, as a Kilobot repeats its message (the copy changes nothing).
    stream = program.stream(image_b, START, every=2)
    repeats = [(tick + 1, kind, data) for tick, kind, data in stream]
    last = stream[-1][0]
    # An event message keeps working during the stream; a second stream after the swap (A's
    # own image) must be ignored: the running image is the receive buffer.
    request = (START + 3, NORMAL, b"requestL\0")
    ignored = program.stream(program.compiled.image, last + 5)
    result = program.run(stream + repeats + [request] + ignored, ignored[-1][0] + 10)
    lines = result.lines
    before, swap, after, statuses = split(lines)
    assert len(result.rx) == 1 + len(stream + repeats + ignored) + 1       # RUN + every message
    swap_step = Program.step_of(lines, arrival(result, stream[-1][2]))
    request_step = Program.step_of(lines, arrival(result, request[2]))
    # (a) A's trace, message event included, until the step after the last chunk came.
    assert before == reference(program.compiled, program.compiled.image, 0, swap_step,
                               received=[(request_step, "EV__requestL")])
    # (b) the swap happens before that step, which is B's first; reception began with the
    # step after chunk 0 came.
    assert swap == "swap ok %d" % len(image_b)
    assert len(before) == swap_step and lines[lines.index(swap) + 1].startswith("1 ")
    first_chunk_step = Program.step_of(lines, arrival(result, stream[0][2]))
    assert lines.index(before[first_chunk_step - 1]) < lines.index("stream receiving") < \
        lines.index(before[first_chunk_step])
    assert statuses == ["stream receiving"]          # no status at all from the ignored stream
    # (c) B from its initial states, to the end (the ignored stream changed nothing).
    assert len(after) > len(ignored) and after == reference(program.compiled, image_b, swap_step, len(after))
    assert before[-1].split()[2].count(",") == 4 and after[0].split()[2].count(",") == 3   # 5 vs 4 supervisors
    # The receive buffer fits the Kilobot's RAM with 1 KB left for the stack.
    sizes = dict(re.findall(r"^\.(data|bss)\s+(\d+)", subprocess.run(
        ["avr-size", "-A", str(program.elf)], capture_output=True, text=True).stdout, re.M))
    assert 512 < int(sizes["data"]) + int(sizes["bss"]) <= 2048 - 1024


@pytest.mark.emulator
def test_corrupted_missing_foreign_and_oversized_streams_do_not_swap(program, image_b):
    parts = chunks(image_b)
    corrupted = bytearray(parts[5])
    corrupted[3] ^= 0x40
    streams = [
        parts[:5] + [bytes(corrupted)] + parts[6:],      # the image's CRC catches it
        parts[:7] + parts[8:],                           # a gap: abandoned at chunk 8
        chunks(image("uav.yaml")),                       # valid, but events A has no code for
        chunks(image("network_worker.yaml"))[:3],        # 1,693 bytes > the 512-byte buffer
        parts[:-1],                                      # the last chunk never comes
    ]
    messages, tick = [], START
    for parts_of_stream in streams:
        messages += [(tick + k, 0x53, p) for k, p in enumerate(parts_of_stream)]
        tick += len(parts_of_stream) + 2
    assert program.chunk_type == 0x53
    result = program.run(messages, tick + 5)
    before, swap, after, statuses = split(result.lines)
    assert swap is None and after == []
    assert len(before) > tick - START
    assert before == reference(program.compiled, program.compiled.image, 0, len(before))   # A kept running
    assert statuses == ["stream receiving", "stream refused %d" % SVM_ERR_CRC,
                        "stream receiving", "stream gap 8",
                        "stream receiving", "stream refused %d" % SVM_ERR_NAMES,
                        "stream receiving", "stream too large 512", "stream gap 2",
                        "stream receiving"]


@pytest.mark.parametrize("compiler", [["gcc", "-O2"], ["clang", "-O2"], ["avr-gcc", "-mmcu=atmega328p", "-Os"]],
                         ids=lambda c: c[0])
def test_the_streaming_build_compiles_without_warning(compiler, tmp_path):
    """The generated application, controller skeleton and Kilobot runtime with SVM_STREAM,
    against the real kilolib's headers, on every C compiler the Kilobot code meets; a flash-only
    build refuses SVM_STREAM with a clear #error."""
    kilolib = kilolib_or_skip()
    write_outputs(tmp_path, generate(compile_inputs([str(SUPERVISOR_A)], name="hl"), "kilobot"))
    limits = re.findall(r"-DSVM_MAX_[A-Z_]+=[0-9]+", (tmp_path / "Makefile").read_text())
    command = [*compiler, *STRICT, *limits, "-DSVM_STREAM", "-I%s" % kilolib, "-c"]
    for source in sorted(p.name for p in tmp_path.glob("hl_*.c")) + ["swarmvm_stream.c", "swarmvm_kilobot.c"]:
        out = subprocess.run([*command, source, "-o", source + ".o"], cwd=tmp_path, capture_output=True, text=True)
        assert (out.returncode, out.stderr) == (0, ""), source
    if compiler[0] == "avr-gcc":
        out = subprocess.run([*command, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "swarmvm_kilobot.c", "-o", "x.o"], cwd=tmp_path,
                             capture_output=True, text=True)
        assert out.returncode != 0 and "SVM_STREAM runs an image from RAM" in out.stderr


COLLIDING = """
num_events: 3
num_supervisors: 1
events: [ EV_broadcastA, EV__broadcastB, EV_u ]
ev_controllable: [ 1, 0, 0 ]
ev_public: [ 1, 1, 0 ]
sup_events: [ [1, 1, 1] ]
sup_init_state: [ 0 ]
sup_current_state: [ 0 ]
sup_data_pos: [ 0 ]
sup_data: [ 3, EV_broadcastA, 0, 0, EV__broadcastB, 0, 0, EV_u, 0, 0 ]
"""


def test_kilobot_refuses_public_events_whose_messages_collide(tmp_path):
    model = tmp_path / "colliding.yaml"
    model.write_text(COLLIDING)
    out = subprocess.run(["swarmvm", "gen", str(model), "--target", "kilobot", "-o", str(tmp_path / "k")],
                         capture_output=True, text=True)
    assert out.returncode == 2 and not (tmp_path / "k").exists()
    assert len(out.stderr.splitlines()) == 1
    assert "EV_broadcastA" in out.stderr and "EV__broadcastB" in out.stderr and "'broadcast'" in out.stderr
    # Other targets carry no 9-byte messages: the same model generates.
    assert subprocess.run(["swarmvm", "gen", str(model), "--target", "c", "-o", str(tmp_path / "c")],
                          capture_output=True).returncode == 0
