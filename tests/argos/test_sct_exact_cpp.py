"""The C++ drop-in (runtime_cpp/sct.h: SCT, SCTPub) steps exactly as the published C++ VM: the
published sct.cpp of ../shared/reference/ (an oracle, built here with yaml-cpp against real
ARGoS, never copied) and the drop-in are built into the same driver (sct_drive.cpp: callbacks
registered the published way, checks with side effects), given the same ARGoS random seed, and
must print the same calls and states for every step of every corpus supervisor. The drop-in
reads the image `swarmvm pack` writes beside the YAML file; the oracle reads the YAML file."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

from checkout import ROOT
from swarmvm import api
from swarmvm.runtime import RUNTIME_CPP

pytestmark = pytest.mark.emulator   # real ARGoS's libraries

REFERENCE = ROOT.parent / "shared" / "reference" / "openswarm-sct-cpp"
DRIVER = Path(__file__).with_name("sct_drive.cpp")
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
STEPS = 1000


@pytest.fixture(scope="module")
def drivers(argos_prefix, tmp_path_factory):
    """(oracle, drop-in) executables and the environment to run them in."""
    if not (REFERENCE / "sct.cpp").is_file() or shutil.which("pkg-config") is None or subprocess.run(
            ["pkg-config", "--exists", "yaml-cpp"]).returncode != 0:
        if os.environ.get("CI") == "true":
            pytest.fail("the published sct.cpp (../shared/reference/) and yaml-cpp (libyaml-cpp-dev) are needed")
        pytest.skip("needs ../shared/reference/openswarm-sct-cpp and yaml-cpp (apt install libyaml-cpp-dev)")
    out = tmp_path_factory.mktemp("sct_exact")
    common = ["g++", "-std=c++17", "-O1", "-I%s" % (argos_prefix / "include"), str(DRIVER)]
    libs = ["-L%s" % (argos_prefix / "lib" / "argos3"), "-largos3core_simulator"]
    oracle, dropin = out / "published", out / "swarmvm"
    subprocess.run([*common[:4], "-w", "-I%s" % REFERENCE, *common[4:], str(REFERENCE / "sct.cpp"), "-o", str(oracle),
                    *libs, "-lyaml-cpp"], check=True)
    subprocess.run([*common[:4], "-Wall", "-Wextra", "-Werror", "-I%s" % RUNTIME_CPP, *common[4:], "-o", str(dropin),
                    *libs], check=True)
    env = dict(os.environ, LD_LIBRARY_PATH=str(argos_prefix / "lib" / "argos3"))
    return oracle, dropin, env


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.stem)
def test_the_drop_in_steps_as_the_published_vm(drivers, path, tmp_path):
    oracle, dropin, env = drivers
    supervisor = tmp_path / "supervisor.yaml"
    shutil.copy(path, supervisor)
    api.write_image([str(supervisor)], str(tmp_path / "supervisor.svm"))
    # The published SCTPub reads ev_shared, which not every file has.
    modes = ["plain"] + (["pub"] if "ev_shared" in yaml.safe_load(path.read_text()) else [])
    for mode in modes:
        runs = [subprocess.run([str(exe), str(supervisor), mode, str(STEPS), "1445"], capture_output=True, text=True,
                               env=env) for exe in (oracle, dropin)]
        assert [r.returncode for r in runs] == [0, 0], runs[0].stderr + runs[1].stderr
        # (ARGoS's log adds a colour reset at exit: only the step lines count)
        want, got = ([line for line in r.stdout.splitlines() if line.startswith("sup:[")] for r in runs)
        assert len(want) == STEPS and " a:" in runs[0].stdout
        for step, (expected, line) in enumerate(zip(want, got), 1):
            assert line == expected, "%s %s: step %d" % (path.stem, mode, step)
        assert got == want
