"""Finding ARGoS: scripts/argos.sh (the prefix it prints, a second call a no-op, exit status 3
when there is neither an ARGoS nor a source archive, a bad ARGOS_PREFIX refused) and the
generated CMakeLists.txt (ARGoS found from the argos3 program on PATH, from CMAKE_PREFIX_PATH,
or by pkg-config where no ARGoSConfig.cmake is found; a clear error without any ARGoS)."""

import os
import shutil
import subprocess
import time

import pytest

from targets.argos.argos_project import ARGOS_SH, CORPUS, NO_ARGOS, generate


def argos_sh(env):
    return subprocess.run([str(ARGOS_SH)], capture_output=True, text=True, env=dict(os.environ, **env))


def test_second_call_finds_the_first_ones_argos(argos_prefix):
    start = time.perf_counter()
    result = argos_sh({})
    assert (result.returncode, result.stdout) == (0, "%s\n" % argos_prefix)
    assert time.perf_counter() - start < 5


def test_no_argos_and_no_archive_is_exit_status_3(tmp_path):
    result = argos_sh({"ARGOS_PREFIX": "", "ARGOS_SRC": str(tmp_path / "argos3-none.tar.xz"),
                       "XDG_CACHE_HOME": str(tmp_path)})
    assert result.returncode == NO_ARGOS
    assert result.stdout == ""
    assert "no ARGoS found and no source archive at %s" % (tmp_path / "argos3-none.tar.xz") in result.stderr


def test_bad_argos_prefix_is_refused(tmp_path):
    result = argos_sh({"ARGOS_PREFIX": str(tmp_path)})
    assert result.returncode == 1
    assert "ARGOS_PREFIX=%s has no bin/argos3" % tmp_path in result.stderr


# The usual places of ARGoSConfig.cmake: ignored so that this machine's installs do not count.
USUAL = ";".join(p + "/share/argos3/cmake" for p in ("/usr/local", "/usr", "/opt", "/opt/local"))


def configure(project, path, tmp_path, *options):
    """CMake configure of a generated project with only PATH and `options` to find ARGoS by
    (pkg-config looks in an empty folder)."""
    env = dict(os.environ, ARGOS_PREFIX="", CMAKE_PREFIX_PATH="", PATH=path, PKG_CONFIG_LIBDIR=str(tmp_path))
    return subprocess.run(["cmake", "-S", str(project.folder), "-B", str(project.folder / "build"),
                           "-DCMAKE_IGNORE_PATH=" + USUAL, *options], capture_output=True, text=True, env=env)


@pytest.mark.parametrize("given", ["argos3 on PATH", "CMAKE_PREFIX_PATH"])
def test_cmake_finds_argos(given, argos_prefix, tmp_path):
    project = generate(CORPUS / "energy_worker.yaml", tmp_path / "project")
    if given == "argos3 on PATH":
        result = configure(project, "%s:%s" % (argos_prefix / "bin", os.environ["PATH"]), tmp_path)
    else:
        result = configure(project, os.environ["PATH"], tmp_path, "-DCMAKE_PREFIX_PATH=%s" % argos_prefix)
    assert result.returncode == 0, result.stderr
    cache = (project.folder / "build" / "CMakeCache.txt").read_text()
    assert "ARGOS_CMAKE_DIR:PATH=%s" % (argos_prefix / "share" / "argos3" / "cmake") in cache


@pytest.mark.skipif(shutil.which("argos3") is not None, reason="an argos3 program is on PATH here")
def test_cmake_without_argos_says_how_to_give_it(tmp_path):
    project = generate(CORPUS / "energy_worker.yaml", tmp_path / "project")
    result = configure(project, os.environ["PATH"], tmp_path)
    assert result.returncode != 0
    assert "ARGoS 3 not found" in result.stderr and "-DARGOS_PREFIX=<prefix>" in result.stderr


@pytest.mark.slow
def test_cmake_falls_back_on_pkg_config(argos_prefix, tmp_path):
    """An ARGoS without ARGoSConfig.cmake but with argos3_simulator.pc (what older releases
    install; written here for the real ARGoS) is found by pkg-config, Lua's headers added."""
    (tmp_path / "argos3_simulator.pc").write_text(
        "prefix=%s\nName: argos3_simulator\nDescription: ARGoS\nVersion: 3\n"
        "Cflags: -I${prefix}/include\nLibs: -L${prefix}/lib/argos3\n" % argos_prefix)
    project = generate(CORPUS / "energy_worker.yaml", tmp_path / "project")
    result = configure(project, os.environ["PATH"], tmp_path, "-DCMAKE_CXX_FLAGS=-Werror")
    assert result.returncode == 0, result.stderr
    assert "ARGOS_CMAKE_DIR:PATH=ARGOS_CMAKE_DIR-NOTFOUND" in (project.folder / "build" / "CMakeCache.txt").read_text()
    build = subprocess.run(["cmake", "--build", str(project.folder / "build"), "--", "VERBOSE=1"],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stdout + build.stderr
    assert "warning" not in (build.stdout + build.stderr).lower()
    assert "-isystem %s/include" % argos_prefix in build.stdout
