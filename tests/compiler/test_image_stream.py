"""Streaming a table image in 9-byte chunks (runtime_c/swarmvm_stream.c, host build): the
receiver completes only on a whole image that passes its checksum, abandons on a gap, restarts
on chunk 0, and refuses an image larger than its buffer."""

import subprocess
from pathlib import Path

import pytest

from swarmvm.compiler.image import chunks
from swarmvm.compiler.pipeline import compile_inputs

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus"
IDLE, RECEIVING, COMPLETE, GAP, TOO_LARGE, INVALID = range(6)
SVM_ERR_CRC = 4


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    exe = tmp_path_factory.mktemp("stream") / "probe"
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2",
                    "-I", str(ROOT / "runtime_c"), str(ROOT / "tests" / "stream" / "stream_probe.c"),
                    str(ROOT / "runtime_c" / "swarmvm_stream.c"), str(ROOT / "runtime_c" / "swarmvm.c"),
                    "-o", str(exe)], check=True)

    def run(parts):
        out = subprocess.run([str(exe)], input=b"".join(parts), capture_output=True, check=True)
        return out.stdout.decode().split()
    return run


def image(name):
    return compile_inputs([str(CORPUS / "openswarm" / name)]).image


def test_a_whole_image_completes_and_loads(probe):
    parts = chunks(image("energy_worker.yaml"))
    statuses = probe(parts)
    assert statuses[:-1] == [str(RECEIVING)] * (len(parts) - 1)
    assert statuses[-1] == "%d:0:10" % COMPLETE


def test_a_missing_chunk_abandons_and_chunk_zero_restarts(probe):
    parts = chunks(image("capbot_demo.yaml"))
    statuses = probe(parts[:3] + parts[4:5] + parts)
    assert statuses[3] == str(GAP)
    assert statuses[-1] == "%d:0:4" % COMPLETE


def test_a_corrupted_chunk_is_caught_by_the_image_checksum(probe):
    parts = chunks(image("uav.yaml"))
    bad = bytearray(parts[5])
    bad[3] ^= 0x40
    statuses = probe(parts[:5] + [bytes(bad)] + parts[6:])
    assert statuses[-1] == "%d:%d" % (INVALID, SVM_ERR_CRC)


def test_an_image_larger_than_the_buffer_is_refused_early(probe):
    parts = chunks(image("network_worker.yaml"))   # 1,693 bytes > 512
    statuses = probe(parts[:4])
    assert statuses[1] == str(TOO_LARGE) and statuses[2] == str(GAP)


def test_chunking_round_trips():
    data = image("hitl_leader.yaml")
    parts = chunks(data)
    assert all(len(p) == 9 for p in parts) and [p[0] for p in parts] == list(range(len(parts)))
    assert b"".join(p[1:] for p in parts)[:len(data)] == data
