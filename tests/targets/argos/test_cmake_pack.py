"""swarmvm_pack() of runtime_cpp/swarmvm_argos.cmake with real CMake: configure, build, edit the
supervisor.yaml, build again, and the image beside it is packed again (never stale: issue 24).
The project folder's name holds a space, a quote and parentheses, so the paths must be quoted
as the function quotes them. (swarmvm_argos.cmake finds ARGoS first, hence the ARGoS fixture.)"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.compiler.runtime_files import RUNTIME_CPP

CORPUS = Path(__file__).resolve().parents[2] / "corpus"


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")
def test_a_cmake_build_packs_the_supervisor_again_when_it_changes(tmp_path, argos_prefix):
    project = tmp_path / "my project's (1)"
    (project / "worker").mkdir(parents=True)
    yaml_path = project / "worker" / "supervisor.yaml"
    yaml_path.write_bytes((CORPUS / "openswarm" / "uav.yaml").read_bytes())
    (project / "CMakeLists.txt").write_text(
        'cmake_minimum_required(VERSION 3.16)\nproject(packing CXX)\n'
        'include("%s/swarmvm_argos.cmake")\nswarmvm_pack(supervisors worker/supervisor.yaml)\n' % RUNTIME_CPP)
    swarmvm = str(Path(sys.executable).parent / "swarmvm")
    build = tmp_path / "build"
    subprocess.run(["cmake", "-S", str(project), "-B", str(build), "-DARGOS_PREFIX=%s" % argos_prefix,
                    "-DSWARMVM_EXECUTABLE=%s" % swarmvm], check=True, capture_output=True)
    image = project / "worker" / "supervisor.svm"

    def build_and_read():
        subprocess.run(["cmake", "--build", str(build)], check=True, capture_output=True)
        return image.read_bytes()

    first = build_and_read()
    assert first == _packed(yaml_path)
    assert build_and_read() == first                                # nothing changed: nothing packed
    yaml_path.write_text(yaml_path.read_text().replace("sup_current_state: [ 0 ]", "sup_current_state: [ 1 ]"))
    second = build_and_read()
    assert second != first and second == _packed(yaml_path)


def _packed(yaml_path):
    """What `swarmvm pack` writes for the file as it now is."""
    return compile_inputs([str(yaml_path)], published=True).packed_image
