"""``swarmvm trace --script -`` reads standard input as a file is read (docs/inspect.md's traces
come from it): any length a file may have, line by line, holding at most errors.MAX_BYTES (and
the line it ends in) of it; within those first bytes a bad line is refused before the first
trace line, as in a file; past them, when it is reached."""

import io
import sys
import tracemalloc

from click.testing import CliRunner

from inspect_cases import FLIPFLOP, NETWORK_WORKER
from swarmvm import api
from swarmvm.readers import event_script
from swarmvm.boundary.errors import MAX_BYTES
from swarmvm.cli.commands import main


def _trace(*args, stdin=None):
    return CliRunner().invoke(main, ["trace", *args], input=stdin)


def test_a_script_over_a_mib_is_read_from_standard_input_as_from_its_file(tmp_path):
    """The issue's case: 20,000 steps of network_worker, 1.09 MB, refused over stdin before."""
    script = api.make_script([str(NETWORK_WORKER)], 20_000, 1)
    assert len(script.encode()) > MAX_BYTES
    (tmp_path / "s.script").write_text(script)
    from_file = _trace(str(NETWORK_WORKER), "--script", str(tmp_path / "s.script"))
    from_stdin = _trace(str(NETWORK_WORKER), "--script", "-", stdin=script)
    assert (from_stdin.exit_code, from_stdin.stderr) == (0, "")
    assert from_stdin.stdout == from_file.stdout and len(from_stdin.stdout.splitlines()) == 20_000


def test_past_the_bytes_held_the_rest_is_streamed(tmp_path, monkeypatch):
    """With 300 bytes held: the same trace as the file's; a bad line within them refused before
    any trace line, one past them when reached, after the steps before it, by its line number."""
    monkeypatch.setattr(event_script, "MAX_BYTES", 300)
    script = api.make_script([str(FLIPFLOP)], 200, 4, density=0.5)
    (tmp_path / "s.script").write_text(script)
    from_file = _trace(str(FLIPFLOP), "--script", str(tmp_path / "s.script")).stdout
    assert len(script.encode()) > 5 * 300 and _trace(str(FLIPFLOP), "--script", "-", stdin=script).stdout == from_file
    lines = script.splitlines(keepends=True)
    early = _trace(str(FLIPFLOP), "--script", "-", stdin="".join(lines[:10] + ["EV_nope\n"] + lines[10:]))
    assert (early.exit_code, early.stdout) == (2, "")
    assert early.stderr == "swarmvm: error: <stdin>: line 11: event EV_nope: unknown event\n"
    late = _trace(str(FLIPFLOP), "--script", "-", stdin="".join(lines[:150] + ["EV_nope\n"] + lines[150:]))
    assert late.exit_code == 2 and late.stdout.splitlines() == from_file.splitlines()[:149]   # line 1: a comment
    assert late.stderr == "swarmvm: error: <stdin>: line 151: event EV_nope: unknown event\n"


def test_what_is_held_stays_bounded(monkeypatch):
    """Rows of a 3.5 MB script on standard input, drawn one by one: under 3 MiB allocated at the
    peak (the old reader refused it; one reading it whole would hold more than the script)."""
    compiled = api.compile_model([str(FLIPFLOP)])
    data = api.make_script([str(FLIPFLOP)], 1000, 4, density=0.5).encode()
    data = data * (3_500_000 // len(data))
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(data)))
    tracemalloc.start()
    try:
        rows = sum(1 for _ in event_script.read_script_rows(event_script.STDIN, compiled.model.events,
                                                                compiled.tables.controllable))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert rows == data.count(b"\n") - data.count(b"#")
    assert peak < 3 * MAX_BYTES, peak
