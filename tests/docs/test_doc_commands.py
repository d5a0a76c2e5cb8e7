"""Every command README.md, docs/ and tests/README.md show is run (issue 27's mechanism: docs that
fail when copied do not come back). Each ```sh, ```bash or ```console block is run as one bash
script (a `cd` in it carries on to its next lines), the blocks of a document in order, in one
scratch folder per document, with the `swarmvm` and `python3` of the Python running the tests
first on PATH: the editable install under `make test`, the wheel's under `make wheel-check`
(scripts/check_wheel.sh). The scratch folder holds what the docs' paths assume of a user's
folder: the repository's examples/ and tests/corpus/, `models/` (the energy worker's published
models) and `supervisor.yaml` (the bundled example) for the robot pages.

A command that needs a robot, a toolchain the suite does not have, or hours is not run: an HTML
comment right above its block says so and why,
    <!-- not-run: REASON -->              the whole block, or
    <!-- not-run "PREFIX": REASON -->     its lines that start with PREFIX (several comments may stack),
and a command neither run nor so marked fails the test. A block showing a synopsis, not a
command, is fenced ```text. Studies pages need the studies extra (skipped without it)."""

import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from checkout import ROOT

DOCUMENTS = [ROOT / "README.md", ROOT / "tests" / "README.md"] + sorted((ROOT / "docs").rglob("*.md"))
SHELL_BLOCK = re.compile(r"((?:^<!-- not-run[^\n]*-->\n)*)^```(?:sh|bash|console)\n(.*?)^```", re.M | re.S)
MARKER = re.compile(r'<!-- not-run(?: "([^"]+)")?: (.+?) -->')


@dataclass(frozen=True)
class Block:
    """One shell block: its commands (continuation lines joined) and what its markers leave out."""
    document: Path
    line: int
    commands: tuple
    skipped: tuple     # (prefix or "" for the whole block, reason)

    def to_run(self):
        if any(prefix == "" for prefix, _ in self.skipped):
            return []
        return [c for c in self.commands if not any(c.startswith(prefix) for prefix, _ in self.skipped)]


def blocks(document):
    text = document.read_text()
    for match in SHELL_BLOCK.finditer(text):
        joined = re.sub(r"\\\n\s*", " ", match.group(2))
        commands = tuple(c for c in (line.strip() for line in joined.splitlines()) if c and not c.startswith("#"))
        skipped = tuple((m.group(1) or "", m.group(2)) for m in MARKER.finditer(match.group(1)))
        yield Block(document, text.count("\n", 0, match.start(2)), commands, skipped)


def scratch_folder(tmp_path):
    """A user's folder as the docs assume it: the example, the corpus, the published models."""
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "corpus").symlink_to(ROOT / "tests" / "corpus")
    (tmp_path / "models").symlink_to(ROOT / "tests" / "corpus" / "synthesis" / "energy_worker")
    shutil.copy(ROOT / "examples" / "energy_worker" / "supervisor.yaml", tmp_path / "supervisor.yaml")
    return tmp_path


def name(document):
    return str(document.relative_to(ROOT))


@pytest.mark.parametrize("document", [d for d in DOCUMENTS if any(blocks(d))], ids=name)
def test_every_command_shown_runs(document, tmp_path):
    if "studies" in document.parts:
        pytest.importorskip("pandas", reason="the studies extra (pip install 'swarmvm[studies]')")
    folder = scratch_folder(tmp_path)
    for block in blocks(document):
        commands = block.to_run()
        if not commands:
            continue
        run = subprocess.run(["bash", "-c", "set -e -o pipefail\n" + "\n".join(commands)], cwd=folder,
                             capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, "%s:%d: %s\n%s" % (name(document), block.line, "\n".join(commands),
                                                        run.stdout[-2000:] + run.stderr[-2000:])


def test_every_command_is_run_or_marked_why():
    """A not-run marker names its reason, and a prefix that matches none of its block's lines
    (a stale marker after the doc changed) is an error too."""
    for document in DOCUMENTS:
        for block in blocks(document):
            for prefix, reason in block.skipped:
                assert len(reason) > 10, "%s:%d: say why %r is not run" % (name(document), block.line, prefix)
                assert prefix == "" or any(c.startswith(prefix) for c in block.commands), \
                    "%s:%d: no command starts with %r" % (name(document), block.line, prefix)


def test_the_extraction_sees_the_blocks_and_markers():
    readme = list(blocks(ROOT / "README.md"))
    assert readme[0].commands[0].startswith("make demo") and readme[0].to_run() == []
    first_run = list(blocks(ROOT / "docs" / "command-line.md"))
    assert any(c.startswith("swarmvm trace examples/") for b in first_run for c in b.to_run())
    kilobot = list(blocks(ROOT / "docs" / "robots" / "kilobot.md"))[0]
    assert kilobot.commands[-1].startswith("make KILOLIB=") and kilobot.to_run()[-1].startswith("cd kilobot_app")
