"""The C++ drop-in never runs a stale image (issue 24, docs/compat.md "Never stale"): given
"x/supervisor.yaml" it reads the x/supervisor.svm that `swarmvm pack` wrote beside it, and
refuses one packed from other bytes of the YAML file, and a missing one, with one message that
names both files and the command that fixes it. The digest it compares is its own SHA-256
(swarmvm::detail::sha256, the runtime has no dependencies), checked here against hashlib at the
lengths where the padding changes. The program is stale_image.cpp, built against swarmvm.hpp
alone (no ARGoS)."""

import hashlib
import random
import subprocess
from pathlib import Path

import pytest

from conformance.cpp_harness import build_program
from swarmvm import api

PROGRAM = Path(__file__).resolve().parent / "stale_image.cpp"
# One supervisor of three states that starts (sup_current_state) in its second: the published
# state string numbers the file's states from 1, so "sup:[2]".
SUPERVISOR = """num_events: 2
num_supervisors: 1
events: [ EV_go, EV_stop ]
ev_controllable: [ 1, 0 ]
sup_events: [ [ 1, 1 ] ]
sup_init_state: [ 0 ]
sup_current_state: [ 1 ]
sup_data_pos: [ 0 ]
sup_data: [ 1, EV_go, 0, 1, 1, EV_go, 0, 2, 1, EV_stop, 0, 0 ]
"""


@pytest.fixture(scope="module")
def program(tmp_path_factory):
    return build_program(PROGRAM, tmp_path_factory.mktemp("stale_image") / "stale_image")


def run(program, verb, *paths):
    return subprocess.run([str(program), verb, *map(str, paths)], check=True, capture_output=True, text=True,
                          timeout=30).stdout.splitlines()


def test_a_stale_or_missing_image_is_refused_with_the_command_that_fixes_it(program, tmp_path):
    good, stale, missing = (tmp_path / name for name in ("good", "stale", "missing"))
    for folder in (good, stale, missing):
        folder.mkdir()
        (folder / "supervisor.yaml").write_text(SUPERVISOR)
    for folder in (good, stale):
        api.write_image([str(folder / "supervisor.yaml")], str(folder / "supervisor.svm"))
    with open(stale / "supervisor.yaml", "a") as handle:
        handle.write("# edited after swarmvm pack\n")

    def fix(folder):
        return "run swarmvm pack %s -o %s" % (folder / "supervisor.yaml", folder / "supervisor.svm")

    assert run(program, "open", *(folder / "supervisor.yaml" for folder in (good, stale, missing))) == [
        "ok sup:[2]",
        "refused: %s is stale: it was packed from another version of %s: %s"
        % (stale / "supervisor.svm", stale / "supervisor.yaml", fix(stale)),
        "refused: cannot read table image %s for %s: %s"
        % (missing / "supervisor.svm", missing / "supervisor.yaml", fix(missing)),
    ]


def test_the_image_alone_runs(program, tmp_path):
    """A robot without the YAML file, or a .svm path given as it is: nothing to compare, the
    image runs (from the file's sup_current_state)."""
    yaml_path, image_path = tmp_path / "supervisor.yaml", tmp_path / "supervisor.svm"
    yaml_path.write_text(SUPERVISOR)
    api.write_image([str(yaml_path)], str(image_path))
    yaml_path.write_text(SUPERVISOR + "# edited\n")
    assert run(program, "open", image_path) == ["ok sup:[2]"]
    yaml_path.unlink()
    assert run(program, "open", yaml_path) == ["ok sup:[2]"]


def test_sha256_matches_hashlib_where_the_padding_changes(program, tmp_path):
    """Lengths around the 56-byte mark (the length field no longer fits the block) and the
    64-byte block, empty included."""
    draw = random.Random(24)
    files = []
    for size in (0, 1, 3, 55, 56, 57, 63, 64, 65, 119, 120, 128, 1000):
        path = tmp_path / ("%d.bin" % size)
        path.write_bytes(bytes(draw.randrange(256) for _ in range(size)))
        files.append(path)
    assert run(program, "sha256", *files) == [hashlib.sha256(path.read_bytes()).hexdigest() for path in files]
