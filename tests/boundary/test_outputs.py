"""Where the output cannot be written: one line naming the path and `-o`, exit status 2, and
nothing written (no partial output, no temporary file left behind). What happens when a file
operation fails half way, or a signal comes, is tests/boundary/test_output_faults.py."""

import os
import socket
import stat
from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

EXAMPLE = str(Path(__file__).resolve().parents[2] / "examples" / "energy_worker" / "supervisor.yaml")


def run(*args):
    result = CliRunner().invoke(main, list(args))
    return result.exit_code, result.output


def every_file(folder):
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*"))


def test_gen_into_a_file_is_one_line(tmp_path):
    blocker = tmp_path / "out"
    blocker.write_text("mine")
    status, output = run("gen", EXAMPLE, "--target", "c", "-o", str(blocker))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a regular file, not a folder\n" % blocker
    assert blocker.read_text() == "mine"


def test_gen_where_no_folder_can_be_made_is_one_line():
    status, output = run("gen", EXAMPLE, "--target", "c", "-o", "/proc/swarmvm-cannot-be-here")
    assert status == 2 and output.count("\n") == 1 and ": -o: cannot write (" in output


def test_pack_onto_a_folder_is_one_line(tmp_path):
    status, output = run("pack", EXAMPLE, "-o", str(tmp_path))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a folder, not a file that can be written\n" % tmp_path


@pytest.mark.parametrize("target", ["c", "argos", "python"])
def test_a_failing_gen_writes_nothing(target, tmp_path):
    """One destination is a folder: the other files are not written either, and no temporary
    file stays behind."""
    out = tmp_path / "out"
    (out / "swarmvm_sub").mkdir(parents=True)
    blocked = {"c": "Makefile", "argos": "swarmvm.hpp", "python": "swarmvm_vm.py"}[target]
    (out / blocked).mkdir()
    status, output = run("gen", EXAMPLE, "--target", target, "-o", str(out))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a folder, not a file that can be written\n" % (
        out / blocked)
    assert every_file(out) == sorted(["swarmvm_sub", blocked])


def make_special(kind, path):
    """A character device (a private /dev/null: the real one is never put at risk), a FIFO or
    a socket at ``path``; the socket's bound handle, to keep it alive."""
    if kind == "character device":
        try:
            os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))
        except PermissionError:
            pytest.skip("making a device node needs root")
    elif kind == "FIFO":
        os.mkfifo(path)
    else:
        bound = socket.socket(socket.AF_UNIX)
        bound.bind(str(path))
        return bound
    return None


@pytest.mark.parametrize("kind", ["character device", "FIFO", "socket"])
def test_pack_onto_a_device_fifo_or_socket_is_refused(kind, tmp_path):
    """`pack -o /dev/null`-like: one line, exit 2, and the special file is still there, untouched
    (it was replaced by a regular file)."""
    special = tmp_path / "x.svm"
    bound = make_special(kind, special)
    before = os.lstat(special)
    status, output = run("pack", EXAMPLE, "-o", str(special))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a %s, not a file that can be written\n" % (special, kind)
    after = os.lstat(special)
    assert (after.st_mode, after.st_ino, after.st_rdev) == (before.st_mode, before.st_ino, before.st_rdev)
    assert every_file(tmp_path) == ["x.svm"]
    if bound is not None:
        bound.close()


def test_gen_into_a_device_is_refused(tmp_path):
    device = tmp_path / "out"
    make_special("character device", device)
    status, output = run("gen", EXAMPLE, "--target", "c", "-o", str(device))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a character device, not a folder\n" % device
    assert stat.S_ISCHR(os.lstat(device).st_mode) and every_file(tmp_path) == ["out"]


@pytest.mark.parametrize("target, kept", [("c", "energy_worker_controller.c"), ("python", "energy_worker_controller.py")])
def test_a_folder_where_the_controller_goes_is_refused(target, kept, tmp_path):
    """The controller skeleton is a file gen keeps when it exists; a folder in its place was
    skipped silently (and the build failed later): now refused, and nothing written."""
    out = tmp_path / "out"
    (out / kept).mkdir(parents=True)
    status, output = run("gen", EXAMPLE, "--target", target, "-o", str(out))
    assert status == 2 and output == "swarmvm: error: %s: -o: is a folder, not a file that can be written\n" % (
        out / kept)
    assert every_file(out) == [kept]


@pytest.mark.parametrize("link", ["folder", "file", "dangling"])
def test_gen_never_writes_through_or_over_a_symbolic_link(link, tmp_path):
    """-o a link to a folder, or a file of the output a link (to a file of the user's, or to
    nowhere): one line naming the link, exit status 2, the link and what it points at untouched,
    nothing written."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    out = tmp_path / "out"
    if link == "folder":
        out.symlink_to(elsewhere)
        named = out
    else:
        out.mkdir()
        named = out / "Makefile"
        if link == "file":
            (elsewhere / "precious").write_text("mine")
        named.symlink_to(elsewhere / "precious")
    status, output = run("gen", EXAMPLE, "--target", "c", "-o", str(out))
    assert status == 2 and output == (
        "swarmvm: error: %s: -o: is a symbolic link: swarmvm does not write through or over one\n" % named)
    assert named.is_symlink() and every_file(elsewhere) == (["precious"] if link == "file" else [])
    assert link != "file" or (elsewhere / "precious").read_text() == "mine"
    assert every_file(out) == ([] if link == "folder" else ["Makefile"])


def test_pack_onto_a_symbolic_link_is_one_line(tmp_path):
    (tmp_path / "real.svm").write_bytes(b"mine")
    (tmp_path / "link.svm").symlink_to(tmp_path / "real.svm")
    status, output = run("pack", EXAMPLE, "-o", str(tmp_path / "link.svm"))
    assert status == 2 and output == (
        "swarmvm: error: %s: -o: is a symbolic link: swarmvm does not write through or over one\n" % (tmp_path / "link.svm"))
    assert (tmp_path / "link.svm").is_symlink() and (tmp_path / "real.svm").read_bytes() == b"mine"


def test_pack_into_a_missing_folder_makes_it(tmp_path):
    """A missing parent of -o is made (it once gave a traceback), and nothing else is left there."""
    target = tmp_path / "a" / "b" / "x.svm"
    status, output = run("pack", EXAMPLE, "-o", str(target))
    assert status == 0 and target.read_bytes()[:4] == b"SVMI" and every_file(tmp_path / "a") == ["b", "b/x.svm"]


# Issue 37, class 2: the umask decides a new file's permissions; a replaced file keeps its own.
def _with_umask(mask, *args):
    old = os.umask(mask)
    try:
        return run(*args)
    finally:
        os.umask(old)


@pytest.mark.parametrize("mask", [0o000, 0o002, 0o022, 0o027, 0o077, 0o277])
def test_new_files_get_the_permissions_the_umask_leaves(mask, tmp_path):
    for args in (["gen", EXAMPLE, "--target", "c", "-o", str(tmp_path / "c")],
                 ["pack", EXAMPLE, "-o", str(tmp_path / "x.svm")],
                 ["export", EXAMPLE, "--format", "yaml", "-o", str(tmp_path / "x.yaml")]):
        status, output = _with_umask(mask, *args)
        assert status == 0, output
    files = [p for p in tmp_path.rglob("*") if p.is_file()]
    assert len(files) > 3
    assert {stat.S_IMODE(p.stat().st_mode) for p in files} == {0o666 & ~mask}


def test_a_replaced_file_keeps_its_permissions(tmp_path):
    out = tmp_path / "x.svm"
    assert _with_umask(0o022, "pack", EXAMPLE, "-o", str(out))[0] == 0
    out.chmod(0o640)
    assert _with_umask(0o000, "pack", EXAMPLE, "-o", str(out))[0] == 0
    assert stat.S_IMODE(out.stat().st_mode) == 0o640


def test_the_umask_is_read_without_being_changed():
    from swarmvm.boundary.output import umask
    old = os.umask(0o037)
    try:
        assert umask() == 0o037 and os.umask(0o037) == 0o037
    finally:
        os.umask(old)
