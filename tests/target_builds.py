"""How the tests build what a target generates, as its record (swarmvm.targets) says: the command
that builds a generated folder in place, and the project's make rule for a corpus supervisor's
linked image. The tests ask these instead of knowing each target's build."""

import subprocess
from pathlib import Path

from checkout import ROOT
from swarmvm.targets import TARGETS
from swarmvm.targets.record import Target


def build_in_place(record: Target, folder: Path, name: str, *options: str) -> subprocess.CompletedProcess:
    """The target's build command run in ``folder`` (``options`` added, ``make`` variables for the
    make-based ones); the caller checks the result."""
    command = [part.format(name=name) for part in record.build]
    assert command, "target %s declares no build command" % record.name
    return subprocess.run([*command, *options], cwd=folder, capture_output=True, text=True)


def measured_targets() -> list[str]:
    """The targets whose linked images the project builds (their record's ``elf.make_rule``)."""
    return sorted(name for name, target in TARGETS.items() if target.elf is not None and target.elf.make_rule)


def image_path(build: Path, target: str, name: str) -> Path:
    """Where the project's make rule puts ``name``'s linked image of ``target`` under ``build``."""
    elf = TARGETS[target].elf
    assert elf is not None and elf.make_rule is not None, "target %s has no make rule for its images" % target
    return Path(elf.make_rule.format(build=build, name=name))


def make_images(build: Path, images: list[Path], *variables: str) -> None:
    """``images`` (image_path's) built by the project's make rules into ``build``."""
    subprocess.run(["make", "-s", "-C", str(ROOT), "BUILD=%s" % build, *variables, *map(str, images)], check=True,
                   capture_output=True, text=True)
