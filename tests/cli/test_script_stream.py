"""`swarmvm script` streams: a script of any length is produced line by line, in constant
memory (a list of ten million rows took 2.6 GB)."""

import itertools
import select
import subprocess
import sys

from checkout import EXAMPLE
from swarmvm import api


def test_the_first_lines_of_an_endless_script_come_at_once():
    lines = list(itertools.islice(api.script_lines([str(EXAMPLE)], 10 ** 15, seed=3), 4))
    assert lines[0].startswith("# swarmvm event script") and len(lines) == 4


def test_the_command_writes_as_it_goes():
    """The command's first lines arrive within seconds of its start, while it is still producing
    the rest of ten million steps (building them first took half a minute and 2.6 GB)."""
    proc = subprocess.Popen([sys.executable, "-m", "swarmvm", "script", str(EXAMPLE), "--steps", str(10 ** 7)],
                            stdout=subprocess.PIPE, text=True)
    try:
        assert select.select([proc.stdout], [], [], 10)[0], "no output within 10 s"
        first = [proc.stdout.readline() for _ in range(3)]
    finally:
        proc.kill()
        proc.wait()
    assert first[0].startswith("# swarmvm event script") and all(line.endswith("\n") for line in first)
