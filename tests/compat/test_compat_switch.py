"""`swarmvm compat-switch` on the build files of two published OpenSwarm ARGoS projects as they
are (../shared/reference/openswarm-layouts/, read in place and copied to a scratch folder only):
the energy study's (the default sct.h) and the multi-human swarm control study's (the mhsc one).

Their controllers' and utility library's sources are not published with the build files: each
scratch project gets stand-ins written here (their first line says so) for every source its
CMakeLists.txt files list, the controllers using their variant's API and including
<utility/sct.h> as the published ones do, plus the published VM of that variant in src/utility/
(../shared/reference/openswarm-sct-cpp*/), as the real projects hold it, and a supervisor. The
fast tests check the edits; the ARGoS tests run docs/compat.md's switch block as it is written
and build the result against real ARGoS (the argos_prefix fixture), with a `python3` first on
PATH that lacks swarmvm, and check the CMake error without a `swarmvm`."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from targets.argos.argos_project import needed_libraries, switch_blocks
from checkout import ROOT
from swarmvm import api
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compat.switch import NOT_FOUND

REFERENCE = ROOT.parent / "shared" / "reference"
LAYOUTS = REFERENCE / "openswarm-layouts"
COMPAT = ROOT / "docs" / "compat.md"
SWARMVM = Path(sys.executable).parent / "swarmvm"
STAND_IN = "Stands in for the unpublished %s of the published project (only its build files are published)."
# (layout, its published VM, variant, how its controllers register a callback)
LAYOUT_VARIANTS = {
    "energy": ("openswarm-sct-cpp", "default", 'std::string("EV_moveToWork")'),
    "mhsc": ("openswarm-sct-cpp-mhsc", "mhsc", 'sct->events["EV_moveToWork"]'),
}
SUPERVISOR = "src/SCT_models/supervisor.yaml"

pytestmark = pytest.mark.skipif(not LAYOUTS.is_dir(), reason="../shared/reference/openswarm-layouts/ (the published "
                                                             "projects' build files) is absent")


def listed_sources(cmake_file):
    """The .h/.cpp files an add_library(...) of a CMakeLists.txt lists."""
    return re.findall(r"^\s*(\w+\.(?:h|cpp))\s*\)?\s*$", cmake_file.read_text(), re.M)


def controller(name, registration):
    header = ("// %s\n#pragma once\n#include <argos3/core/control_interface/ci_controller.h>\n#include <utility/sct.h>\n"
              "#include <string>\n\nclass C%s : public argos::CCI_Controller {\npublic:\n"
              "    void Init(argos::TConfigurationNode& t_node) override;\n    void ControlStep() override;\n"
              "private:\n    void Callback(void* data);\n    SCT* sct = nullptr;\n};\n"
              % (STAND_IN % ("controllers/%s/%s.h" % (name, name)), name))
    source = ('// %s\n#include "%s.h"\n\nvoid C%s::Init(argos::TConfigurationNode& t_node) {\n'
              '    std::string path;\n    argos::GetNodeAttribute(argos::GetNode(t_node, "SCT"), "path", path);\n'
              "    sct = new SCTPub(path);\n    sct->add_callback(this, %s, &C%s::Callback, NULL, NULL);\n}\n\n"
              "void C%s::ControlStep() { sct->run_step(); }\n\nvoid C%s::Callback(void*) {}\n\n"
              'REGISTER_CONTROLLER(C%s, "%s_controller")\n'
              % (STAND_IN % ("controllers/%s/%s.cpp" % (name, name)), name, name, registration, name, name, name,
                 name, name))
    return header, source


def write_project(layout, folder, utility_uses_yaml=False):
    """A copy of the layout's build files with stand-ins for what is not published, the
    published VM of its variant in src/utility/, and the energy worker's supervisor."""
    reference, _, registration = LAYOUT_VARIANTS[layout]
    shutil.copytree(LAYOUTS / layout, folder)
    src = folder / "src"
    for cmake_file in (src / "controllers").glob("*/CMakeLists.txt"):
        header, source = controller(cmake_file.parent.name, registration)
        (cmake_file.parent / (cmake_file.parent.name + ".h")).write_text(header)
        (cmake_file.parent / (cmake_file.parent.name + ".cpp")).write_text(source)
    for name in listed_sources(src / "utility" / "CMakeLists.txt"):
        if name.startswith("sct."):
            shutil.copy(REFERENCE / reference / name, src / "utility" / name)
        elif name.endswith(".h"):
            (src / "utility" / name).write_text("// %s\n#pragma once\n" % (STAND_IN % ("utility/" + name)))
        else:
            uses = "#include <yaml-cpp/yaml.h>\n" if utility_uses_yaml and name == "pid.cpp" else ""
            (src / "utility" / name).write_text('// %s\n%s#include "%s"\nint %s_stand_in() { return 0; }\n'
                                                % (STAND_IN % ("utility/" + name), uses, name[:-4] + ".h",
                                                   name[:-4]))
    # The projects' protos/ need protobuf and .proto files, neither published nor installed here.
    (src / "cmake").mkdir()
    (src / "cmake" / "FindProtobuf.cmake").write_text(
        "# %s\nset(Protobuf_FOUND TRUE)\nset(PROTOBUF_LIBRARIES \"\")\n" % (STAND_IN % "protobuf installation"))
    (src / "protos" / "generated" / "stand_in.pb.cc").write_text(
        "// %s\nint protos_stand_in() { return 0; }\n" % (STAND_IN % "protoc output"))
    (folder / SUPERVISOR).parent.mkdir()
    shutil.copy(ROOT / "tests" / "corpus" / "openswarm" / "energy_worker.yaml", folder / SUPERVISOR)
    return folder


def switch(folder, *options):
    return subprocess.run([str(SWARMVM), "compat-switch", str(folder), *options], capture_output=True, text=True)


def snapshot(folder):
    return {p.relative_to(folder): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("layout", sorted(LAYOUT_VARIANTS))
def test_the_switch_edits_the_published_build_files_once(layout, tmp_path):
    project = write_project(layout, tmp_path / "project")
    before = snapshot(project)
    result = switch(project)
    assert result.returncode == 0, result.stderr
    changed = sorted(Path(line).relative_to(project).as_posix() for line in result.stdout.splitlines())
    controllers = sorted(p.relative_to(project).as_posix() for p in (project / "src" / "controllers").glob("*/*.h"))
    assert changed == sorted(["src/CMakeLists.txt", "src/utility/CMakeLists.txt", *controllers])
    assert "(%s variant)" % LAYOUT_VARIANTS[layout][1] in result.stderr

    utility = (project / "src" / "utility" / "CMakeLists.txt").read_text()
    published = (LAYOUTS / layout / "src" / "utility" / "CMakeLists.txt").read_text()
    assert "sct.cpp" not in utility and "${SWARMVM_RUNTIME_DIR}/sct.h" in utility
    assert [s for s in listed_sources(project / "src" / "utility" / "CMakeLists.txt")] == \
        [s for s in listed_sources(LAYOUTS / layout / "src" / "utility" / "CMakeLists.txt") if not s.startswith("sct.")]
    assert "yaml-cpp" in published and "yaml-cpp" not in utility
    assert "argos3plugin_simulator_genericrobot" in utility
    top = (project / "src" / "CMakeLists.txt").read_text()
    assert top.index("swarmvm_argos.cmake") < top.index("add_subdirectory(controllers)")
    assert ("SWARMVM_SCT_VARIANT_MHSC" in top) == (layout == "mhsc")
    assert 'swarmvm_pack(supervisors "SCT_models/supervisor.yaml")' in top
    for header in controllers:
        text = (project / header).read_text()
        assert "#include <sct.h>" in text and "utility/sct.h" not in text
    after = snapshot(project)
    assert {p for p in after if after[p] != before.get(p)} == {Path(p) for p in changed}

    again = switch(project)
    assert again.returncode == 0 and again.stdout == ""
    assert again.stderr == "swarmvm: note: %s is switched already: nothing changed\n" % project
    assert snapshot(project) == after


def test_yaml_cpp_stays_linked_when_another_utility_source_needs_it(tmp_path):
    project = write_project("energy", tmp_path / "project", utility_uses_yaml=True)
    api.compat_switch(str(project))
    utility = (project / "src" / "utility" / "CMakeLists.txt").read_text()
    assert "sct.cpp" not in utility and "yaml-cpp" in utility


def test_the_variant_is_read_from_the_controllers_without_the_published_header(tmp_path):
    project = write_project("mhsc", tmp_path / "project")
    (project / "src" / "utility" / "sct.h").unlink()
    assert api.compat_switch(str(project)).variant == "mhsc"
    other = write_project("energy", tmp_path / "other")
    assert api.compat_switch(str(other), variant="mhsc").variant == "mhsc"


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")
def test_supervisor_paths_reach_cmake_as_written(tmp_path):
    project = write_project("energy", tmp_path / "project")
    odd = project / "src" / 'my "odd" ${HOME} dir' / "supervisor.yaml"
    odd.parent.mkdir()
    shutil.copy(project / SUPERVISOR, odd)
    api.compat_switch(str(project))
    call = next(line for line in (project / "src" / "CMakeLists.txt").read_text().splitlines()
                if line.startswith("swarmvm_pack("))
    script = tmp_path / "read_back.cmake"
    script.write_text('function(swarmvm_pack target)\n  foreach(each IN LISTS ARGN)\n    message("${each}")\n'
                      "  endforeach()\nendfunction()\n%s\n" % call)
    said = subprocess.run(["cmake", "-P", str(script)], capture_output=True, text=True, check=True).stderr
    assert said.splitlines() == ["SCT_models/supervisor.yaml", 'my "odd" ${HOME} dir/supervisor.yaml'], said


def test_cmake_dir_prints_the_folder_cmake_includes():
    result = subprocess.run([str(SWARMVM), "cmake-dir"], capture_output=True, text=True, check=True)
    folder = Path(result.stdout.rstrip("\n"))
    assert result.stdout.count("\n") == 1
    assert (folder / "swarmvm_argos.cmake").is_file() and (folder / "sct.h").is_file()


def test_a_folder_that_is_not_such_a_project_is_refused_in_one_line(tmp_path):
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "CMakeLists.txt").write_text("project(x)\n")
    result = switch(tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.count("\n") == 1
    assert "not an OpenSwarm ARGoS project: looked for src/CMakeLists.txt and src/utility/CMakeLists.txt" \
        in result.stderr and "src/utility/CMakeLists.txt is missing" in result.stderr


def test_nothing_is_written_when_one_file_cannot_be(tmp_path):
    project = write_project("energy", tmp_path / "project")
    header = project / "src" / "controllers" / "charger" / "charger.h"
    elsewhere = tmp_path / "charger.h"
    header.rename(elsewhere)
    header.symlink_to(elsewhere)                          # output never writes through a link
    before = snapshot(project)
    result = switch(project)
    assert result.returncode == 2 and "symbolic link" in result.stderr
    assert snapshot(project) == before


def stand_in_plugins(folder, argos_prefix):
    """Empty libraries for the projects' own ARGoS robot plugins (an e-puck with a charger, a
    leader e-puck), which the ARGoS here does not have: a folder for the linker's LIBRARY_PATH."""
    folder.mkdir()
    source = folder / "plugin.cpp"
    source.write_text("// %s\n" % (STAND_IN % "ARGoS robot plugin"))
    for name in ("epuckcharger", "epuckleader"):
        subprocess.run(["g++", "-shared", "-fPIC", str(source), "-o", str(folder / ("libargos3plugin_simulator_%s.so"
                                                                                     % name))], check=True)
    return folder


def user_environment(tmp_path, argos_prefix, with_swarmvm=True):
    """A shell whose first python3 lacks swarmvm; ARGoS found by CMAKE_PREFIX_PATH (which the
    published projects read from the environment); with or without swarmvm on PATH."""
    fake = tmp_path / "fake_python"
    fake.mkdir()
    (fake / "python3").write_text("#!/bin/sh\necho \"No module named 'swarmvm'\" >&2\nexit 1\n")
    (fake / "python3").chmod(0o755)
    rest = [d for d in os.environ["PATH"].split(os.pathsep) if d and not (Path(d) / "swarmvm").exists()]
    path = [str(fake)] + ([str(SWARMVM.parent)] if with_swarmvm else []) + rest
    plugins = stand_in_plugins(tmp_path / "plugins", argos_prefix)
    return dict(os.environ, PATH=os.pathsep.join(path), CMAKE_PREFIX_PATH=str(argos_prefix),
                LIBRARY_PATH=str(plugins), ARGOS_PREFIX="")


def configure_before(project, argos_prefix, env):
    """The project configured as it was published (the user's build folder, whose cache keeps
    where ARGoS is: ARGoS's own config wants ARGOS_CMAKE_DIR outside the usual prefixes)."""
    result = subprocess.run(["cmake", "-S", "src", "-B", "build", "-DARGOS_CMAKE_DIR=%s" % (
        argos_prefix / "share" / "argos3" / "cmake")], cwd=project, env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]


@pytest.mark.emulator
@pytest.mark.slow
@pytest.mark.parametrize("layout", sorted(LAYOUT_VARIANTS))
def test_the_documented_switch_builds_the_published_layout_in_argos(argos_prefix, layout, tmp_path):
    project = write_project(layout, tmp_path / "project")
    env = user_environment(tmp_path, argos_prefix)
    assert subprocess.run(["python3", "-c", "import swarmvm"], env=env, capture_output=True).returncode != 0
    configure_before(project, argos_prefix, env)
    blocks = [text for language, text in switch_blocks() if language == "sh"]
    assert blocks[0].splitlines()[0] == "swarmvm compat-switch ."
    for text in blocks:
        result = subprocess.run(["bash", "-euo", "pipefail", "-c", text], cwd=project, env=env, capture_output=True,
                                text=True)
        assert result.returncode == 0, "%s\n%s%s" % (text, result.stdout[-3000:], result.stderr[-3000:])
    built = {p.name for p in (project / "build").rglob("*.so")}
    controllers = {p.name for p in (project / "src" / "controllers").iterdir() if p.is_dir()}
    assert built >= {"libutility.so"} | {"lib%s.so" % c for c in controllers}, built
    assert not any(name.startswith("libyaml-cpp") for name in needed_libraries(project))
    image = (project / SUPERVISOR).with_suffix(".svm")          # packed by the build (swarmvm_pack)
    assert image.read_bytes() == compile_inputs([str(project / SUPERVISOR)], published=True).packed_image

    again = subprocess.run(["swarmvm", "compat-switch", "."], cwd=project, env=env, capture_output=True, text=True)
    assert again.returncode == 0 and again.stdout == "" and "nothing changed" in again.stderr


@pytest.mark.emulator
@pytest.mark.parametrize("executable", ["not on PATH", "given wrong"])
def test_without_swarmvm_cmake_stops_with_the_documented_error(argos_prefix, executable, tmp_path):
    project = write_project("energy", tmp_path / "project")
    env = user_environment(tmp_path, argos_prefix, with_swarmvm=False)
    configure_before(project, argos_prefix, env)
    api.compat_switch(str(project))
    options = ["-DSWARMVM_EXECUTABLE=%s" % (tmp_path / "no_swarmvm")] if executable == "given wrong" else []
    result = subprocess.run(["cmake", "-S", "src", "-B", "build", *options], cwd=project, env=env, capture_output=True,
                            text=True)
    assert result.returncode != 0
    said = " ".join(result.stderr.split())
    documented = NOT_FOUND.split("): ", 1)[1]
    assert documented in " ".join(COMPAT.read_text().split())
    assert "swarmvm not found" in said and documented in said, result.stderr
    if executable == "not on PATH":
        assert NOT_FOUND.replace("${SWARMVM_EXECUTABLE}", "SWARMVM_EXECUTABLE-NOTFOUND") in said
