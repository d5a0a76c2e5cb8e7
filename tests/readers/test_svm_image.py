"""Images are first-class inputs (issue 40, point 3): every verb that reads a supervisor reads a
``.svm`` image too, as the set it was packed from; what it cannot do from an image (anything
named after events, from a ``--no-names`` image) it says in one line."""

import subprocess
from pathlib import Path

import pytest

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "corpus"
SUPERVISORS = sorted(CORPUS.glob("*/*.yaml"))
AUTOMATA = sorted((CORPUS / "automata").glob("energy_worker_Sloc?.xml"))


def swarmvm(*args, cwd=None):
    return subprocess.run(["swarmvm", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def packed(inputs, tmp_path, name="logic.svm", *options):
    out = tmp_path / name
    result = swarmvm("pack", *inputs, "-o", out, *options)
    assert result.returncode == 0, result.stderr
    return out


@pytest.mark.parametrize("inputs", [[p] for p in SUPERVISORS] + [AUTOMATA], ids=lambda i: i[0].stem)
def test_an_image_packs_back_to_itself(inputs, tmp_path):
    """The set rebuilt from an image, its order and source sections included, compiles to the
    image again, byte for byte (so exact mode from an image is exact mode from its file)."""
    first = packed(inputs, tmp_path, "first.svm")
    again = packed([first], tmp_path, "again.svm")
    assert again.read_bytes() == first.read_bytes()


@pytest.mark.parametrize("path", [CORPUS / "openswarm" / "energy_worker.yaml",
                                  CORPUS / "nadzoru2" / "probabilistic_example.yaml",
                                  CORPUS / "nadzoru2" / "public_example.yaml"], ids=lambda p: p.stem)
def test_gen_from_an_image_writes_what_gen_from_its_file_writes(path, tmp_path):
    image = packed([path], tmp_path)
    for target in sorted(TARGETS):
        a, b = tmp_path / ("yaml-" + target), tmp_path / ("svm-" + target)
        for source, out in ((path, a), (image, b)):
            result = swarmvm("gen", source, "--target", target, "-o", out, "--name", "model")
            assert result.returncode == 0, (target, result.stderr)
        files = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file())
        assert files == sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file())
        for f in files:         # the same bytes, but for the header naming the file it came from
            assert (b / f).read_bytes().replace(image.name.encode(), path.name.encode()) == (a / f).read_bytes(), f


def test_the_other_verbs_read_an_image_as_its_file(tmp_path):
    path = CORPUS / "openswarm" / "energy_worker.yaml"
    image = packed([path], tmp_path)
    assert swarmvm("equiv", path, image).returncode == 0
    for verb in (["script", "--steps", "30", "--seed", "5"], ["check", "--properties"]):
        from_yaml, from_svm = swarmvm(*verb, path), swarmvm(*verb, image)
        assert from_svm.returncode == from_yaml.returncode == 0, from_svm.stderr
        assert from_svm.stdout == from_yaml.stdout.replace(str(path), str(image)).replace(path.name, image.name)
    for out, source in (("a.yaml", path), ("b.yaml", image)):
        assert swarmvm("export", source, "--format", "yaml", "-o", tmp_path / out).returncode == 0
    assert (tmp_path / "a.yaml").read_bytes() == (tmp_path / "b.yaml").read_bytes()
    assert compile_inputs([str(image)]).model.events == compile_inputs([str(path)]).model.events
    script = tmp_path / "s.txt"
    script.write_text(swarmvm("script", image, "--steps", "10").stdout)
    trace = tmp_path / "r.trace"
    trace.write_text(swarmvm("trace", image, "--script", script).stdout)
    assert swarmvm("inspect", image, trace, "-o", tmp_path / "page.html").returncode == 0


def test_an_image_without_names_says_in_one_line_what_it_cannot_do(tmp_path):
    image = packed([CORPUS / "openswarm" / "energy_worker.yaml"], tmp_path, "bare.svm", "--no-names")
    assert swarmvm("check", image).returncode == 0                      # check and trace read it
    for verb in (["gen", image, "--target", "c", "-o", tmp_path / "c"], ["equiv", image, image],
                 ["script", image], ["export", image, "--format", "yaml", "-o", tmp_path / "x.yaml"]):
        result = swarmvm(*verb)
        assert result.returncode == 2 and result.stderr.count("\n") == 1, result.stderr
        assert "%s: image: packed with --no-names" % image in result.stderr
    assert not (tmp_path / "c").exists() and not (tmp_path / "x.yaml").exists()


def test_a_damaged_image_is_refused_with_the_runtimes_reason(tmp_path):
    image = packed([CORPUS / "openswarm" / "energy_worker.yaml"], tmp_path)
    raw = bytearray(image.read_bytes())
    raw[-1] ^= 0xFF
    image.write_bytes(bytes(raw))
    result = swarmvm("gen", image, "--target", "c", "-o", tmp_path / "c")
    assert result.returncode == 2 and "%s: image:" % image in result.stderr and "checksum" in result.stderr
