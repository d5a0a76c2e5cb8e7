"""The documented switch of an OpenSwarm ARGoS project from the published VM to swarmvm's sct.h
(docs/compat.md, "Switching an OpenSwarm ARGoS project over"), for both published variants of
sct.h, in real ARGoS.

For each variant, a project in the published layout (tests/targets/argos/switch_project/: the common
CMake files, `utility` library and loop functions, plus the variant's controller and experiment,
written here in the published style and using the variant's API) gets the published sct.h and
sct.cpp of that variant from ../shared/reference/ (oracles, copied into the scratch project only)
and the corpus supervisor its study used. It is built against real ARGoS and yaml-cpp and run for
a few seeds; then the shell blocks of that docs section are run in it as written (`swarmvm
compat-switch .`, then CMake), it is built again in the same build folder (its cache keeps where ARGoS is,
as a user's does) and run again: every seed's ARGoS log (each robot's state string and callback
calls at every step, then a summary) and position trace must be byte-identical."""

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import pytest
from targets.argos.argos_project import ARGOS_SH, needed_libraries, switch_blocks

from checkout import ROOT
from swarmvm import api
from swarmvm.compiler.runtime_files import RUNTIME_CPP

pytestmark = [pytest.mark.emulator, pytest.mark.slow]   # builds and runs projects in real ARGoS

FIXTURE = Path(__file__).with_name("switch_project")
REFERENCE = ROOT.parent / "shared" / "reference"
MHSC_DEFINE = "SWARMVM_SCT_VARIANT_MHSC"
SEEDS = (1, 2, 3)
SUPERVISOR = Path("src/SCT_models/supervisor.yaml")


@dataclass(frozen=True)
class Variant:
    """A published variant of sct.h and the project written here for it."""
    folder: str        # in switch_project/: its controller and experiment
    reference: str     # its published sct.h / sct.cpp in ../shared/reference/
    supervisor: str    # the corpus supervisor of the study that used it
    experiment: str    # experiments/<experiment>.argos
    calls: str         # a callback call its runs must make (the runs are not idle)


VARIANTS = (Variant("energy", "openswarm-sct-cpp", "energy_worker.yaml", "worker", " charge"),
            Variant("mhsc", "openswarm-sct-cpp-mhsc", "hitl_leader.yaml", "leader", " respond"))


def write_project(variant, folder):
    """The variant's project in the published layout, with the published VM in src/utility/."""
    shutil.copytree(FIXTURE / "common", folder)
    shutil.copytree(FIXTURE / variant.folder, folder, dirs_exist_ok=True)
    for name in ("sct.h", "sct.cpp"):
        shutil.copy(REFERENCE / variant.reference / name, folder / "src" / "utility" / name)
    (folder / SUPERVISOR).parent.mkdir()
    shutil.copy(ROOT / "tests" / "corpus" / "openswarm" / variant.supervisor, folder / SUPERVISOR)


def run(command, folder, env):
    result = subprocess.run(command, cwd=folder, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    assert result.returncode == 0, "%s failed:\n%s" % (command[:3], result.stdout)


def run_experiments(variant, folder):
    """{file name: bytes} of every seed's ARGoS log and position trace."""
    outputs = {}
    for seed in SEEDS:
        tree = ET.parse(folder / "experiments" / (variant.experiment + ".argos"))
        tree.getroot().find("framework/experiment").set("random_seed", str(seed))
        tree.getroot().find("loop_functions").set("trace", "trace_%d.txt" % seed)
        tree.write(folder / "experiments" / ("seed_%d.argos" % seed))
        status, log = run_argos(folder, seed)
        assert status == 0, log
        outputs["log_%d" % seed] = log
        outputs["trace_%d.txt" % seed] = (folder / ("trace_%d.txt" % seed)).read_bytes()
    return outputs


def run_argos(folder, seed):
    """(exit status, LOG and LOGERR output) of experiments/seed_SEED.argos, run headless."""
    result = subprocess.run([str(ARGOS_SH), "run", "-n", "-c", "experiments/seed_%d.argos" % seed, "-l", "log.txt",
                             "-e", "err.txt"], cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return result.returncode, (folder / "log.txt").read_bytes() + (folder / "err.txt").read_bytes() + result.stdout


@pytest.fixture(scope="module")
def tools():
    """Skips (fails under CI) without the published VMs, yaml-cpp or readelf."""
    missing = [what for what, there in (
        ("../shared/reference/ (the published VMs)", all((REFERENCE / v.reference / "sct.cpp").is_file()
                                                          for v in VARIANTS)),
        ("yaml-cpp (apt install libyaml-cpp-dev)", shutil.which("pkg-config") is not None and subprocess.run(
            ["pkg-config", "--exists", "yaml-cpp"]).returncode == 0),
        ("readelf", shutil.which("readelf") is not None)) if not there]
    if missing:
        if os.environ.get("CI") == "true":
            pytest.fail("needed: " + ", ".join(missing))
        pytest.skip("needs " + ", ".join(missing))


def test_the_section_has_the_steps_this_test_applies():
    assert [language for language, _ in switch_blocks()] == ["sh", "sh", "text"]
    assert switch_blocks()[0][1].startswith("swarmvm compat-switch .\n")


@pytest.mark.parametrize("variant", VARIANTS, ids=lambda v: v.folder)
def test_the_documented_switch_runs_as_the_published_vm(argos_prefix, tools, variant, tmp_path):
    project = tmp_path / "project"
    write_project(variant, project)
    # The user's shell: python3 and swarmvm of the environment swarmvm is installed in.
    env = dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent), os.environ["PATH"]]))
    run(["cmake", "-S", "src", "-B", "build", "-DCMAKE_PREFIX_PATH=%s" % argos_prefix,
         "-DARGOS_CMAKE_DIR=%s" % (argos_prefix / "share" / "argos3" / "cmake")], project, env)
    run(["cmake", "--build", "build"], project, env)
    assert any(name.startswith("libyaml-cpp") for name in needed_libraries(project))
    published = run_experiments(variant, project)
    steps = published["log_1"].decode().count("\nstep ")
    assert steps == 6 * 400 and variant.calls.encode() in published["log_1"], published["log_1"][-2000:]

    for language, text in switch_blocks():
        if language == "sh":
            run(["bash", "-euo", "pipefail", "-c", text], project, env)
    assert "sct.cpp" not in (project / "src" / "utility" / "CMakeLists.txt").read_text()
    assert not any(name.startswith("libyaml-cpp") for name in needed_libraries(project))

    switched = run_experiments(variant, project)
    for name, expected in published.items():
        assert switched[name] == expected, "%s %s differs" % (variant.folder, name)

    # Without the image beside the supervisor, the experiment stops saying how to make it.
    (project / SUPERVISOR.with_suffix(".svm")).unlink()
    status, output = run_argos(project, SEEDS[0])
    assert status != 0
    assert ("run swarmvm pack %s -o %s" % (SUPERVISOR, SUPERVISOR.with_suffix(".svm"))).encode() in output, output


@pytest.mark.parametrize("mhsc", [False, True], ids=["default", "mhsc"])
def test_each_variant_has_its_api_and_refuses_the_other(argos_prefix, mhsc, tmp_path):
    source = FIXTURE / "variant_api.cpp"
    compile_ = ["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-I%s" % (argos_prefix / "include"),
                "-I%s" % RUNTIME_CPP] + (["-D" + MHSC_DEFINE] if mhsc else [])
    wrong = subprocess.run([*compile_, "-fsyntax-only", "-DOTHER_VARIANT", str(source)], capture_output=True,
                           text=True)
    hint = "build without " + MHSC_DEFINE if mhsc else "build with -D" + MHSC_DEFINE
    assert wrong.returncode != 0 and hint in wrong.stderr, wrong.stderr

    supervisor = tmp_path / "leader.yaml"
    shutil.copy(ROOT / "tests" / "corpus" / "openswarm" / "hitl_leader.yaml", supervisor)
    api.write_image([str(supervisor)], str(supervisor.with_suffix(".svm")))
    program = tmp_path / "variant_api"
    subprocess.run([*compile_, str(source), "-o", str(program), "-L%s" % (argos_prefix / "lib" / "argos3"),
                    "-largos3core_simulator"], check=True)
    result = subprocess.run([str(program), str(supervisor)], capture_output=True, text=True, check=True,
                            env=dict(os.environ, LD_LIBRARY_PATH=str(argos_prefix / "lib" / "argos3")))
    # After one step (seed 1) each of hitl_leader's five supervisors is in its state 0, which the
    # mhsc variant prints as 0 and the default one as 1.
    assert result.stdout.splitlines()[:2] == ["sup:[0,0,0,0,0]" if mhsc else "sup:[1,1,1,1,1]",
                                              "no event named 'EV_typo' in this supervisor"]
