"""A generated Kilobot project measured with no hand-written declaration (issue 36, point 4): gen
writes <name>.footprint.json where the Makefile builds <name>.elf, and `swarmvm footprint` reads
it by itself (the stack bounded without --indirect), runs its event script with --cycles, and
refuses, in one line with status 2, a sidecar that is not of the image's build (another
supervisor's, another target's, damaged). The README's measure commands are run as written."""

import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from checkout import EXAMPLE, ROOT
from targets.kilobot.needs import board_or_skip, kilolib_or_skip
from swarmvm import api
from swarmvm.boundary.output import write_outputs
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.footprint.measure import FootprintError
from swarmvm.footprint.sidecar import SCRIPT_SEED
from swarmvm.targets import TARGETS, generate

FORAGER = ROOT / "examples" / "learning" / "supervisor.yaml"


def _sh_blocks(readme: str, heading: str) -> list[str]:
    """The command lines of the ```sh blocks under ``## heading``, comments dropped."""
    section = readme.split("## %s\n" % heading, 1)[1].split("\n## ", 1)[0]
    return [line.split("#", 1)[0].strip() for block in re.findall(r"```sh\n(.*?)```", section, re.S)
            for line in block.splitlines() if line.split("#", 1)[0].strip()]


@pytest.fixture(scope="module")
def project(tmp_path_factory) -> Path:
    """The example generated as `robot` and built by its Makefile, as its README says."""
    kilolib = kilolib_or_skip()
    folder = tmp_path_factory.mktemp("kilobot") / "robot"
    write_outputs(folder, generate(compile_inputs([str(EXAMPLE)], name="robot"), "kilobot"))
    build = _sh_blocks((folder / "README.md").read_text(), "Build")
    assert build == ["make KILOLIB=/path/to/kilolib"]
    subprocess.run([*build[0].replace("/path/to/kilolib", str(kilolib)).split(), "robot.elf"], cwd=folder,
                   check=True, capture_output=True)
    return folder


def _footprint(folder: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["swarmvm", "footprint", *args], cwd=folder, capture_output=True, text=True)


@pytest.mark.emulator
def test_the_readme_measures_the_image_with_no_declaration(project, tmp_path):
    board_or_skip()
    commands = _sh_blocks((project / "README.md").read_text(), "Measure")
    assert commands == ["swarmvm footprint robot.elf", "swarmvm footprint robot.elf --cycles robot.footprint.json"]
    assert "--indirect" not in " ".join(commands)
    for command in commands:
        result = subprocess.run([*command.split(), "--json", str(tmp_path / "fp.json")], cwd=project,
                                capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        image = json.loads((tmp_path / "fp.json").read_text())["images"][0]
        assert "unknown" not in image["stack"] and image["stack"]["step"] > 0 and image["stack"]["total"] > 0
        assert image["indirect"]["svm_step"] == ["svm_kilobot_app_dispatch", "dispatch"]
    cycles = image["cycles"]
    assert cycles["script"] == "robot.footprint.json" and cycles["steps"] == TARGETS["kilobot"].elf.script_steps
    # the script is what `swarmvm script --steps 40 --seed 1` prints: the digest --cycles records of that file
    script = api.make_script([str(EXAMPLE)], cycles["steps"], SCRIPT_SEED)
    assert cycles["script_sha256"] == hashlib.sha256(script.encode()).hexdigest()


def test_explicit_declarations_add_to_the_sidecars(project):
    footprint = api.measure_footprint([str(project / "robot.elf")], indirect=["svm_step=my_dispatch"])[0]
    assert footprint.indirect["svm_step"] == ("svm_kilobot_app_dispatch", "dispatch", "my_dispatch")
    assert footprint.indirect["kilo_start"] == ("setup", "loop")


def _copy(project: Path, tmp_path: Path) -> Path:
    folder = tmp_path / "copy"
    folder.mkdir()
    for path in project.iterdir():
        if path.suffix in (".elf", ".su", ".json"):
            shutil.copy(path, folder / path.name)
    return folder


def _refused(folder: Path, *args: str) -> str:
    result = _footprint(folder, "robot.elf", *args)
    assert result.returncode == 2 and result.stdout == "", result
    assert len(result.stderr.splitlines()) == 1, result.stderr
    return result.stderr


def test_a_sidecar_not_of_the_images_build_is_refused(project, tmp_path):
    folder = _copy(project, tmp_path)
    sidecar = folder / "robot.footprint.json"
    good = json.loads(sidecar.read_text())
    # another supervisor's sidecar beside this image: its digest is not the image's
    other = generate(compile_inputs([str(FORAGER)], name="robot"), "kilobot")["robot.footprint.json"][0]
    sidecar.write_bytes(other)
    said = _refused(folder)
    assert "robot.footprint.json: tables_sha256: " in said and "is not the digest of the table image in" in said
    elf = str(folder / "robot.elf")
    for key, value, message in (("target", "capbot", "target: a sidecar of a capbot image"),
                                ("version", 2, "version: a footprint sidecar of version 2"),
                                ("indirect", ["svm_step"], "indirect[0]: 'svm_step' is not CALLER=TARGET"),
                                ("script", "EV_atWork", "script: must be a list of strings"),
                                ("extra", 1, "extra: unknown key")):
        sidecar.write_text(json.dumps(dict(good, **{key: value})))
        with pytest.raises(FootprintError, match=re.escape("robot.footprint.json: " + message)):
            api.measure_footprint([elf])
    sidecar.write_text(json.dumps(good)[:-9])
    with pytest.raises(FootprintError, match="robot.footprint.json: not a JSON file"):
        api.measure_footprint([elf])
    # given to --cycles, another build's sidecar is refused too, before anything runs
    sidecar.write_text(json.dumps(good))
    (folder / "other.footprint.json").write_bytes(other)
    assert "other.footprint.json: tables_sha256: " in _refused(folder, "--cycles", "other.footprint.json")
