"""The table image: round trip, layout facts, and every refusal a runtime must make."""

import struct
from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.compiler.pipeline import compile_inputs

CORPUS = Path(__file__).parent.parent / "corpus"
SUPERVISORS = sorted(CORPUS.glob("*/*.yaml"))


def test_crc_check_value(vm):
    assert vm.crc16(b"123456789") == 0x6F91


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.name)
def test_image_round_trips_the_tables(vm, path):
    compiled = compile_inputs([str(path)])
    image, tables = vm.Image.parse(compiled.image), compiled.tables
    assert image.names == list(compiled.model.events)
    assert (image.controllable, image.public) == (tables.controllable, tables.public)
    assert image.sup_alphabet == list(tables.sup_alphabet)
    assert image.state_defined == list(tables.state_defined)
    assert image.targets == list(tables.targets)
    assert (image.probs is None) == (tables.probs is None)
    assert compiled.image[:4] == b"SVMI" and struct.unpack_from("<H", compiled.image, 14)[0] == len(compiled.image)


def test_largest_corpus_tables_fit_in_two_kilobytes():
    compiled = compile_inputs([str(CORPUS / "openswarm" / "network_worker.yaml")])
    assert len(compiled.image) < 2048
    assert compiled.tables.state_width == 1 and compiled.tables.mask_bytes == 4


def test_without_names_the_image_is_smaller_and_binds_by_index(vm):
    path = str(CORPUS / "openswarm" / "uav.yaml")
    named, bare = compile_inputs([path]).image, compile_inputs([path], names=False).image
    assert len(bare) < len(named)
    image = vm.Image.parse(bare)
    assert image.names is None and image.event_name(3) == "EV_3"
    with pytest.raises(KeyError):
        image.event_index("bid")


def _reseal(vm, raw):
    raw = bytearray(raw)
    raw[-2:] = struct.pack("<H", vm.crc16(bytes(raw[:-2])))
    return bytes(raw)


@pytest.mark.parametrize("damage, message", [
    (lambda vm, b: b[:10], "truncated"),
    (lambda vm, b: b"XVMI" + b[4:], "not a swarmvm table image"),
    (lambda vm, b: _reseal(vm, b[:4] + bytes([2]) + b[5:]), "format version 2"),
    (lambda vm, b: b[:20] + bytes([b[20] ^ 1]) + b[21:], "checksum mismatch"),
    (lambda vm, b: b + b"\0", "length field"),
    (lambda vm, b: _reseal(vm, b[:13] + bytes([9]) + b[14:]), "header inconsistent"),
])
def test_damaged_images_are_refused(vm, damage, message):
    good = compile_inputs([str(CORPUS / "openswarm" / "capbot_demo.yaml")]).image
    with pytest.raises(vm.ImageError, match=message):
        vm.Image.parse(damage(vm, good))


def test_pack_and_check_an_image(tmp_path):
    out = tmp_path / "logic.svm"
    result = CliRunner().invoke(main, ["pack", str(CORPUS / "openswarm" / "energy_worker.yaml"), "-o", str(out)])
    assert result.exit_code == 0 and result.stdout == "%s: %d bytes\n" % (out, out.stat().st_size)
    result = CliRunner().invoke(main, ["check", str(out)])
    assert result.exit_code == 0
    assert "| %s | 10 | 4 | 32 | 124 | %d |" % (out, out.stat().st_size) in result.stdout
    raw = out.read_bytes()
    out.write_bytes(raw[:-1] + bytes([raw[-1] ^ 0xFF]))
    result = CliRunner().invoke(main, ["check", str(out)])
    assert result.exit_code == 2
    assert result.stderr.startswith("swarmvm: error: %s: image: image checksum mismatch" % out)
