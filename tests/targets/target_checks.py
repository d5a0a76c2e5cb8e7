"""What every target must do, checked through the ``swarmvm`` command so that a target found
through SWARMVM_TARGET_PATH is checked exactly as the package's own: gen renders every file its
record lists, the same bytes on every run, keeps the user's files, refuses the model names every
target refuses, and the record's docs page exists and shows how to generate it."""

import os
import subprocess
from pathlib import Path

from checkout import EXAMPLE, ROOT
from swarmvm.footprint.sidecar import SUFFIX
from swarmvm.targets import README
from swarmvm.targets.record import Target

NAME = "energy_worker"


def swarmvm(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(["swarmvm", *args], capture_output=True, text=True, env=env)


def tree(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def expected_files(record: Target, name: str) -> set[str]:
    """The image, every template's output and every runtime copy (no learned checks asked); the
    README of a target that describes its files, the footprint sidecar of one whose images
    footprint measures."""
    outputs = [out for _, out, _ in record.templates] + [out for _, out in record.copies]
    extra = {README} if record.readme is not None else set()
    extra |= {name + SUFFIX} if record.elf is not None else set()
    return {"%s.svm" % name} | {out.format(name=name) for out in outputs} | extra


def gen(record: Target, folder: Path, *options: str, env: dict[str, str] | None = None,
        model: Path = EXAMPLE) -> subprocess.CompletedProcess:
    return swarmvm("gen", str(model), "--target", record.name, "-o", str(folder), *options, env=env)


def check_renders_deterministically(record: Target, tmp_path: Path, env: dict[str, str] | None = None) -> None:
    first, second = tmp_path / "first", tmp_path / "second"
    for folder in (first, second):
        run = gen(record, folder, "--name", NAME, env=env)
        assert run.returncode == 0, run.stderr
    assert tree(first) == tree(second)
    assert set(tree(first)) == expected_files(record, NAME)
    assert not any(str(tmp_path).encode() in data or str(ROOT).encode() in data for data in tree(first).values())
    kept = [out.format(name=NAME) for _, out, keep in record.templates if keep]
    for out in kept:
        (first / out).write_text("edited\n")
    assert gen(record, first, "--name", NAME, env=env).returncode == 0
    assert all((first / out).read_text() == "edited\n" for out in kept)


def check_refuses_names_as_the_others(record: Target, tmp_path: Path, env: dict[str, str] | None = None) -> None:
    """A model name every target refuses (a C keyword, the runtime's prefix) is refused for this
    one too, in the same words, and nothing is written."""
    for name in ("int", "svm_robot"):
        refused = gen(record, tmp_path / name, "--name", name, env=env)
        reference = swarmvm("gen", str(EXAMPLE), "--target", "c", "-o", str(tmp_path / "c"), "--name", name)
        assert refused.returncode == reference.returncode == 2
        assert refused.stderr == reference.stderr and not (tmp_path / name).exists()


def check_docs_page(record: Target) -> None:
    page = Path(record.page) if os.path.isabs(record.page) else ROOT / "docs" / record.page
    assert page.is_file(), "target %s: no docs page %s" % (record.name, record.page)
    assert "--target %s" % record.name in page.read_text(encoding="utf-8")
