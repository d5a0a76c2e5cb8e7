"""A first ARGoS build (about 10 minutes) says what it does while it runs (issue 27, point 1):
scripts/argos.sh reports its stages and make's per cent on stderr, keeps the whole output in a
log it names, and `make argos-demo`'s Python (argos_project.find_argos) passes those lines on as
they come instead of capturing them. The build here is a stand-in archive: a small CMake
project laid out as ARGoS's source (src/CMakeLists.txt) that installs a bin/argos3."""

import os
import re
import subprocess
import tarfile

from targets.argos.argos_project import ARGOS_SH, find_argos

FAKE_SOURCE = """cmake_minimum_required(VERSION 3.10)
project(fake_argos C)
foreach(i RANGE 1 12)
  file(WRITE ${CMAKE_BINARY_DIR}/part${i}.c "int part${i}(void) { return ${i}; }\\n")
  add_library(part${i} STATIC ${CMAKE_BINARY_DIR}/part${i}.c)
endforeach()
file(WRITE ${CMAKE_BINARY_DIR}/argos3 "#!/bin/sh\\n")
install(PROGRAMS ${CMAKE_BINARY_DIR}/argos3 DESTINATION bin)
install(DIRECTORY DESTINATION include/argos3)
"""


def fake_archive(tmp_path):
    """argos3-fake.tar.xz: one top folder holding src/CMakeLists.txt, as ARGoS's archive does."""
    source = tmp_path / "argos3-fake" / "src"
    source.mkdir(parents=True)
    (source / "CMakeLists.txt").write_text(FAKE_SOURCE)
    archive = tmp_path / "argos3-fake.tar.xz"
    with tarfile.open(archive, "w:xz") as tar:
        tar.add(tmp_path / "argos3-fake", arcname="argos3-fake")
    return archive


def environment(tmp_path):
    """ARGOS_SRC given explicitly (so that it is built even though an ARGoS is installed here),
    the cache in tmp_path."""
    return dict(os.environ, ARGOS_PREFIX="", ARGOS_SRC=str(fake_archive(tmp_path)), XDG_CACHE_HOME=str(tmp_path))


def test_argos_sh_reports_the_stages_and_the_per_cent(tmp_path):
    env = environment(tmp_path)
    result = subprocess.run([str(ARGOS_SH)], capture_output=True, text=True, env=env)
    # The jobs nproc gives in that environment (it honours OMP_NUM_THREADS, which a study's
    # worker may have set in this process), as argos.sh asks it.
    jobs = int(subprocess.run(["nproc"], capture_output=True, text=True, env=env, check=True).stdout)
    prefix = tmp_path / "swarmvm" / "argos3-fake"
    log = tmp_path / "swarmvm" / "argos3-fake.build.log"
    assert (result.returncode, result.stdout) == (0, "%s\n" % prefix), result.stderr
    said = result.stderr.splitlines()
    assert said[0].startswith("argos.sh: building ARGoS from %s into %s, once" % (tmp_path / "argos3-fake.tar.xz",
                                                                                   prefix))
    assert said[0].endswith("full output: %s" % log)
    stages = [line for line in said if not line.startswith("argos.sh: compiling ARGoS: ")]
    assert stages[1:] == ["argos.sh: unpacking the source", "argos.sh: configuring (cmake)",
                          "argos.sh: compiling (make -j%d)" % jobs, "argos.sh: installing",
                          "argos.sh: built; installed in %s" % prefix]
    per_cent = [int(m.group(1)) for m in map(re.compile(r"argos.sh: compiling ARGoS: (\d+)%$").match, said) if m]
    assert len(per_cent) >= 3 and per_cent[-1] == 100
    assert all(later - earlier >= 5 for earlier, later in zip(per_cent, per_cent[1:-1])), per_cent
    assert "Building C object" in log.read_text() and "Building C object" not in result.stderr


def test_find_argos_passes_the_build_lines_on_as_they_come(tmp_path, monkeypatch, capfd):
    for key, value in environment(tmp_path).items():
        monkeypatch.setenv(key, value)
    status, prefix, stderr = find_argos()
    assert (status, prefix) == (0, tmp_path / "swarmvm" / "argos3-fake")
    shown = capfd.readouterr().err
    assert "argos.sh: compiling ARGoS: 100%" in shown and shown == stderr
