"""Where the output cannot be written: one line naming the path and `-o`, exit status 2, and
nothing written (no partial output, no temporary file left behind)."""

from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli import main

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
    assert status == 2 and output == "swarmvm: error: %s: -o: cannot write (File exists)\n" % blocker
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
