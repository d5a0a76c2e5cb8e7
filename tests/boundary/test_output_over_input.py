"""An output that is one of the inputs is refused before anything is written (issue 37, class 3):
the output layer refuses to replace a file the command read (by device and inode, so every
spelling of its path and every hard link is the same file) or to write into a folder of inputs
it read. `pack x.yaml -o x.yaml` used to replace the supervisor by its image."""

import os
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from swarmvm.cli.commands import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
AUTOMATA = sorted((ROOT / "tests" / "corpus" / "automata").glob("energy_worker_Sloc?.xml"))


def run(*args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    return result.exit_code, result.stderr


def _spelling(parts: list[str], detours: list[int]) -> str:
    """A relative path to the same file, with ``./`` and ``sub/..`` detours at the given places."""
    out = []
    for i, part in enumerate(parts):
        for kind in (d for d in detours if d % (len(parts) + 1) == i):
            out.append("." if kind % 2 else "sub/..")
        out.append(part)
    return "/".join(out)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.integers(0, 50), max_size=4), st.sampled_from(["pack", "export"]))
def test_every_spelling_of_an_input_as_the_output_is_refused(tmp_path, monkeypatch, detours, verb):
    (tmp_path / "d" / "sub").mkdir(parents=True, exist_ok=True)
    (tmp_path / "sub").mkdir(exist_ok=True)
    source = tmp_path / "d" / "x.yaml"
    source.write_bytes(EXAMPLE.read_bytes())
    monkeypatch.chdir(tmp_path)
    output = _spelling(["d", "x.yaml"], detours)
    args = ["pack", "d/x.yaml", "-o", output] if verb == "pack" else ["export", "d/x.yaml", "--format", "yaml",
                                                                      "-o", output]
    status, stderr = run(*args)
    assert status == 2 and stderr.count("\n") == 1 and "is an input of this command" in stderr, (output, stderr)
    assert source.read_bytes() == EXAMPLE.read_bytes()


def test_a_hard_link_to_the_input_is_the_input(tmp_path):
    source = tmp_path / "x.yaml"
    source.write_bytes(EXAMPLE.read_bytes())
    os.link(source, tmp_path / "other.yaml")
    status, stderr = run("pack", source, "-o", tmp_path / "other.yaml")
    assert status == 2 and "is an input of this command" in stderr
    assert (tmp_path / "other.yaml").read_bytes() == EXAMPLE.read_bytes()


def test_gen_does_not_replace_the_image_it_reads(tmp_path):
    """gen writes <name>.svm: from x.svm into x.svm's own folder, that is the input."""
    image = tmp_path / "x.svm"
    assert run("pack", EXAMPLE, "-o", image)[0] == 0
    before = image.read_bytes()
    status, stderr = run("gen", image, "--target", "c", "-o", tmp_path)
    assert status == 2 and "%s: -o: is an input of this command" % image in stderr
    assert image.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["x.svm"]


def test_no_output_goes_into_a_folder_of_inputs(tmp_path):
    folder = tmp_path / "automata"
    folder.mkdir()
    for path in AUTOMATA:
        (folder / path.name).write_bytes(path.read_bytes())
    status, stderr = run("export", folder, "--format", "gen", "-o", folder)
    assert status == 2 and "is a folder of inputs this command read" in stderr
    assert sorted(p.name for p in folder.iterdir()) == sorted(p.name for p in AUTOMATA)


def test_outputs_beside_the_input_are_fine(tmp_path):
    source = tmp_path / "x.yaml"
    source.write_bytes(EXAMPLE.read_bytes())
    assert run("pack", source, "-o", tmp_path / "x.svm")[0] == 0
    assert run("gen", source, "--target", "c", "-o", tmp_path)[0] == 0
    assert source.read_bytes() == EXAMPLE.read_bytes()


def test_each_api_call_has_its_own_record(tmp_path):
    """What one call read does not bind the next: reading x then writing x in another call works."""
    from swarmvm import api
    source = tmp_path / "x.yaml"
    source.write_bytes(EXAMPLE.read_bytes())
    api.check([str(source)])
    api.export([str(EXAMPLE)], "yaml", str(source))
    assert source.read_bytes() != b""
