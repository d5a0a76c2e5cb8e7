"""The input layer beyond the verbs (issue 37, point 1): the runtimes' own loaders and the
footprint readers open regular files only, without waiting, and read a bounded number of bytes.

Each kind of path a loader can be handed that is not a regular file — a FIFO with no writer (a
plain ``open`` waits on it for ever), ``/dev/zero`` (endless), a folder — is given to every
loader: the Python runtime's (``Image.load``, ``SCT`` on a ``supervisor.yaml``, the app's event
scripts, a saved learned policy, run as a robot runs them: without the compiler importable), the
C++ runtime's (``Image::load``, ``load_beside``), and the footprint readers (ELF files, ``.su``
files). Each must return within seconds with one line naming the file and what it is. Every
probe runs in a subprocess with a timeout, so the old code (which blocked on the FIFO) fails
instead of hanging the suite."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from conformance.cpp_harness import build_program
from swarmvm import api
from swarmvm.compiler.runtime_files import RUNTIME_PY_DIR

HERE = Path(__file__).resolve().parent
SUPERVISOR = """num_events: 2
num_supervisors: 1
events: [ EV_go, EV_stop ]
ev_controllable: [ 1, 0 ]
sup_events: [ [ 1, 1 ] ]
sup_init_state: [ 0 ]
sup_current_state: [ 0 ]
sup_data_pos: [ 0 ]
sup_data: [ 1, EV_go, 0, 1, 1, EV_go, 0, 2, 1, EV_stop, 0, 0 ]
"""
PROMPTLY = 20       # seconds: far more than any refusal takes; the old code never returned

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(),
                                reason="needs FIFOs and /dev/zero (a Unix system)")


@pytest.fixture
def hostile(tmp_path):
    """{kind: path} of the paths that are not regular files, and the kind each is refused as."""
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    folder = tmp_path / "folder"
    folder.mkdir()
    return {"a FIFO": fifo, "a character device": Path("/dev/zero"), "a folder": folder}


def _python_runtime(probe: str) -> list[str]:
    """Lines the probe prints, run as a robot runs the runtime: ``-S`` (no site-packages, so no
    swarmvm compiler to compile a YAML file with), the runtime's folder first on the path."""
    code = "import sys\nsys.path.insert(0, %r)\n%s" % (str(RUNTIME_PY_DIR), textwrap.dedent(probe))
    run = subprocess.run([sys.executable, "-S", "-c", code], capture_output=True, text=True, timeout=PROMPTLY)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout.splitlines()


def test_python_image_load_refuses_what_is_not_a_regular_file(hostile):
    probe = """
        import swarmvm_format as f
        for path in sys.argv[1:] if len(sys.argv) > 1 else %r:
            try:
                f.Image.load(path)
            except OSError as exc:
                print(type(exc).__name__, str(exc))
        """ % ([str(p) for p in hostile.values()],)
    lines = _python_runtime(probe)
    assert lines == ["FileKindError %s: is %s, not a regular file" % (path, kind) for kind, path in hostile.items()]


def test_python_sct_refuses_a_supervisor_yaml_that_is_not_a_regular_file(tmp_path, hostile):
    """``SCT("x/supervisor.yaml")`` beside a packed image reads the YAML file to see whether the
    image is stale: a FIFO there (the issue's example, which never returned) or a device is
    refused in one line; the packed image itself under a FIFO's name too."""
    cases = []
    for index, (kind, path) in enumerate(hostile.items()):
        folder = tmp_path / ("case%d" % index)
        folder.mkdir()
        (folder / "supervisor.yaml").write_text(SUPERVISOR)
        api.write_image([str(folder / "supervisor.yaml")], str(folder / "supervisor.svm"))
        (folder / "supervisor.yaml").unlink()
        if kind == "a folder":
            (folder / "supervisor.yaml").mkdir()
        elif kind == "a FIFO":
            os.mkfifo(folder / "supervisor.yaml")
        else:
            (folder / "supervisor.yaml").symlink_to(path)
        cases.append((kind, str(folder / "supervisor.yaml")))
    image_fifo = tmp_path / "fifo_image"
    image_fifo.mkdir()
    os.mkfifo(image_fifo / "supervisor.svm")
    (image_fifo / "supervisor.yaml").write_text(SUPERVISOR)
    probe = """
        import swarmvm_vm as vm
        for path in %r:
            try:
                vm.SCT(path)
                print("accepted", path)
            except OSError as exc:
                print(str(exc))
        """ % ([path for _, path in cases] + [str(image_fifo / "supervisor.yaml")],)
    lines = _python_runtime(probe)
    assert lines == ["%s: is %s, not a regular file" % (path, kind) for kind, path in cases] + [
        "%s: is a FIFO, not a regular file" % (image_fifo / "supervisor.svm")]


def test_python_app_script_and_learned_policy_refuse_what_is_not_a_regular_file(hostile):
    probe = """
        import swarmvm_app as app, swarmvm_learn as learn, swarmvm_format as f
        for path in %r:
            try:
                app.read_script(path, ["EV_go"])
            except SystemExit as exc:
                print("script", exc)
            try:
                learn.LearnedPolicy.load(None, path)
            except OSError as exc:
                print("policy", exc)
        """ % ([str(p) for p in hostile.values()],)
    lines = _python_runtime(probe)
    expected = []
    for kind, path in hostile.items():
        refusal = "%s: is %s, not a regular file" % (path, kind)
        expected += ["script %s: cannot read the script (%s)" % (path, refusal), "policy " + refusal]
    assert lines == expected


def test_python_read_file_reads_one_byte_over_its_limit(tmp_path):
    """The bound: a regular file is read to ``limit`` + 1 bytes, never further."""
    from runtime_py import swarmvm_format as f
    path = tmp_path / "big"
    path.write_bytes(bytes(1000))
    assert len(f.read_file(path, 10)) == 11 and len(f.read_file(path, 5000)) == 1000


@pytest.fixture(scope="module")
def cpp_loader(tmp_path_factory):
    return build_program(HERE / "runtime_loader.cpp", tmp_path_factory.mktemp("loader") / "runtime_loader")


def _cpp(program, verb, *paths):
    run = subprocess.run([str(program), verb, *map(str, paths)], capture_output=True, text=True, timeout=PROMPTLY)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout.splitlines()


def test_cpp_image_load_refuses_what_is_not_a_regular_file(cpp_loader, hostile, tmp_path):
    good = tmp_path / "good.svm"
    (tmp_path / "good.yaml").write_text(SUPERVISOR)
    api.write_image([str(tmp_path / "good.yaml")], str(good))
    big = tmp_path / "big.svm"
    big.write_bytes(bytes(70000))
    lines = _cpp(cpp_loader, "image", good, *hostile.values(), big, tmp_path / "missing.svm")
    assert lines[0] == "ok 2"
    assert lines[1:4] == ["refused: table image %s: is %s, not a regular file" % (path, kind)
                          for kind, path in hostile.items()]
    assert "over the format's maximum" in lines[4]
    assert lines[5] == "refused: cannot read table image %s (No such file or directory)" % (tmp_path / "missing.svm")


def test_cpp_load_beside_refuses_what_is_not_a_regular_file(cpp_loader, hostile, tmp_path):
    """The drop-in SCT's ``load_beside``: the image and the supervisor.yaml whose digest it
    compares, each a FIFO, a device or a folder in turn."""
    paths, expected = [], []
    for index, (kind, hostile_path) in enumerate(hostile.items()):
        for which in ("supervisor.yaml", "supervisor.svm"):
            folder = tmp_path / ("case%d_%s" % (index, which))
            folder.mkdir()
            (folder / "supervisor.yaml").write_text(SUPERVISOR)
            api.write_image([str(folder / "supervisor.yaml")], str(folder / "supervisor.svm"))
            (folder / which).unlink()
            if kind == "a folder":
                (folder / which).mkdir()
            elif kind == "a FIFO":
                os.mkfifo(folder / which)
            else:
                (folder / which).symlink_to(hostile_path)
            paths.append(folder / "supervisor.yaml")
            what = "supervisor file" if which == "supervisor.yaml" else "table image"
            expected.append("refused: %s %s: is %s, not a regular file" % (what, folder / which, kind))
    assert _cpp(cpp_loader, "beside", *paths) == expected


def test_the_footprint_readers_refuse_what_is_not_a_regular_file(hostile, tmp_path):
    """``swarmvm footprint`` given a FIFO, a device or a folder for an ELF ends in one line,
    exit 2; the ``.su`` and cycle readers likewise (in the API: InputError)."""
    for kind, path in hostile.items():
        elf = tmp_path / ("x_%d.elf" % len(kind))
        elf.symlink_to(path) if kind != "a FIFO" else os.mkfifo(elf)
        run = subprocess.run([sys.executable, "-m", "swarmvm", "footprint", str(elf)], capture_output=True,
                             text=True, timeout=PROMPTLY)
        assert (run.returncode, run.stderr) == (2, "swarmvm: error: %s: is %s, not a regular file\n" % (elf, kind))
    probe = textwrap.dedent("""
        import sys
        from pathlib import Path
        from swarmvm.boundary.errors import InputError
        from swarmvm.footprint import cycles, measure, stack
        for path in sys.argv[1:]:
            for name, read in (("su", lambda: stack.read_su([Path(path)])), ("symbols", lambda: cycles._symbols(path, set())),
                               ("functions", lambda: stack._functions(Path(path))), ("image", lambda: measure.table_image(path))):
                try:
                    read()
                except InputError as exc:
                    print(name, exc)
        """)
    run = subprocess.run([sys.executable, "-c", probe, *map(str, hostile.values())], capture_output=True, text=True,
                         timeout=PROMPTLY)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.splitlines() == ["%s %s: is %s, not a regular file" % (name, path, kind)
                                       for kind, path in hostile.items()
                                       for name in ("su", "symbols", "functions", "image")]


def test_an_elf_over_its_bound_is_refused_before_it_is_read(tmp_path, monkeypatch):
    """ELF files have their own bound (ELF_MAX_BYTES, docs/limits.md), checked on the size
    before any byte is read."""
    from swarmvm.boundary import errors
    from swarmvm.footprint import measure
    elf = tmp_path / "big.elf"
    with open(elf, "wb") as handle:
        handle.truncate(errors.ELF_MAX_BYTES + 1)       # sparse: no disk used
    with pytest.raises(errors.InputError, match="file is %d bytes, over the %d-byte limit"
                       % (errors.ELF_MAX_BYTES + 1, errors.ELF_MAX_BYTES)):
        measure.table_image(str(elf))


def test_python_runtime_write_file_is_whole_or_nothing_with_the_umask(tmp_path, monkeypatch):
    """The runtime's one writer (a saved learned policy): a new file's mode from the umask, a
    replaced file's kept, and a write that fails leaves the old file and no temporary file."""
    from runtime_py import swarmvm_format as f
    old = os.umask(0o077)
    try:
        f.write_file(tmp_path / "new.json", b"new")
    finally:
        os.umask(old)
    assert (tmp_path / "new.json").stat().st_mode & 0o777 == 0o600
    kept = tmp_path / "kept.json"
    kept.write_bytes(b"old")
    kept.chmod(0o640)
    f.write_file(kept, b"newer")
    assert kept.read_bytes() == b"newer" and kept.stat().st_mode & 0o777 == 0o640

    def full(fd, data):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(f.os, "write", full)
    with pytest.raises(OSError, match="No space"):
        f.write_file(kept, b"lost")
    monkeypatch.undo()
    assert kept.read_bytes() == b"newer" and sorted(p.name for p in tmp_path.iterdir()) == ["kept.json", "new.json"]
    os.mkfifo(tmp_path / "fifo")
    with pytest.raises(f.FileKindError, match="is a FIFO, not a regular file"):
        f.write_file(tmp_path / "fifo", b"x")
