"""Generated tables refuse a runtime of another format version, at compile or import time.

As nanopb's generated code checks its runtime's version: the C tables header (``#error``), the
ARGoS image header (``static_assert``) and the Python table module (``ImportError``) each name
the format version they hold. Each test generates a target, then gives it a runtime that claims
the next version (the copied format file edited: swarmvm_format.h, .hpp or .py) and expects a clear refusal; the unedited
target builds or imports."""

import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.compiler.runtime_files import image_format

F = image_format()
SUPERVISOR = Path(__file__).resolve().parents[1] / "corpus" / "openswarm" / "energy_worker.yaml"
MESSAGE = "format version %d" % F.FORMAT_VERSION


def _generate(target, out):
    result = CliRunner().invoke(main, ["gen", str(SUPERVISOR), "--target", target, "-o", str(out)])
    assert result.exit_code == 0, result.output


def _next_version(path, current, bumped):
    """Edit the copied runtime file to claim the next format version."""
    text = path.read_text()
    assert text.count(current) == 1, "%s: %r not found once" % (path.name, current)
    path.write_text(text.replace(current, bumped))


def test_c_tables_refuse_another_runtime_version(tmp_path):
    _generate("c", tmp_path)
    compile_tables = ["gcc", "-std=c99", "-fsyntax-only", "energy_worker_tables.c"]
    assert subprocess.run(compile_tables, cwd=tmp_path, capture_output=True).returncode == 0
    version = F.FORMAT_VERSION
    _next_version(tmp_path / "swarmvm_format.h", "#define SVM_FORMAT_VERSION %du" % version,
                  "#define SVM_FORMAT_VERSION %du" % (version + 1))
    run = subprocess.run(compile_tables, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode != 0 and "#error" in run.stderr and MESSAGE in run.stderr, run.stderr


def test_cpp_image_header_refuses_another_runtime_version(tmp_path):
    _generate("argos", tmp_path)
    (tmp_path / "use.cpp").write_text('#include "energy_worker_image.hpp"\nint main() { return 0; }\n')
    compile_image = ["g++", "-std=c++17", "-fsyntax-only", "use.cpp"]
    assert subprocess.run(compile_image, cwd=tmp_path, capture_output=True).returncode == 0
    version = F.FORMAT_VERSION
    _next_version(tmp_path / "swarmvm_format.hpp", "kFormatVersion = %d;" % version, "kFormatVersion = %d;" % (version + 1))
    run = subprocess.run(compile_image, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode != 0 and "static assertion failed" in run.stderr and MESSAGE in run.stderr, run.stderr


def test_python_tables_refuse_another_runtime_version(tmp_path):
    _generate("python", tmp_path)
    importer = [sys.executable, "-c", "import energy_worker_tables"]
    run = subprocess.run(importer, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    version = F.FORMAT_VERSION
    _next_version(tmp_path / "swarmvm_format.py", "FORMAT_VERSION = %d\n" % version,
                  "FORMAT_VERSION = %d\n" % (version + 1))
    run = subprocess.run(importer, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode != 0 and "ImportError" in run.stderr and MESSAGE in run.stderr, run.stderr
