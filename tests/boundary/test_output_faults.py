"""Output is a transaction, shown in the manner of SQLite's I/O error tests.

Every file operation of swarmvm.boundary.output goes through ``output.OPS``. A clean run of a ``gen``
(or a ``pack``) over an older output counts its operations; then, for every k, the run is
repeated with the k-th operation failing (EIO, then ENOSPC) or with SIGINT arriving at it,
and afterwards the folder must be byte for byte the old output or the new one, with no
temporary or backup file, and the error one line naming a real destination. A real SIGTERM or
SIGINT sent to a ``swarmvm gen`` process paused at chosen operations must leave the same."""

import contextlib
import errno
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from swarmvm import api
from swarmvm.boundary import output

CORPUS = Path(__file__).resolve().parents[1] / "corpus" / "openswarm"
NEW, OLD = str(CORPUS / "energy_worker.yaml"), str(CORPUS / "network_worker.yaml")
STAGING = {"mkdir", "open", "write", "fsync", "chmod"}      # operations after which a signal ends staging


class Faults:
    """``output.OPS`` wrapped: each operation's name recorded in ``seen``, and ``fault`` called
    just before the ``at``-th one (counting from 1). fsync is counted but not done: durability
    is not what these tests can see, and it is most of their time."""

    def __init__(self, real, at=0, fault=None):
        self.real, self.at, self.fault, self.seen = real, at, fault, []

    def __getattr__(self, name):
        operation = getattr(self.real, name)

        def counted(*args):
            self.seen.append(name)
            if len(self.seen) == self.at:
                self.fault()
            return None if name == "fsync" else operation(*args)
        return counted


@contextlib.contextmanager
def operations(wrapper):
    """``output.OPS`` replaced by ``wrapper`` while in the ``with``."""
    real, output.OPS = output.OPS, wrapper
    try:
        yield wrapper
    finally:
        output.OPS = real


def fail_with(code):
    def fault():
        raise OSError(code, os.strerror(code))
    return fault


def interrupt():
    signal.raise_signal(signal.SIGINT)


# Each scenario: (make the old output in tmp/out, write the new one there), both through the API.
SCENARIOS = {
    "gen_c": (lambda out: api.generate_target([OLD], "c", str(out)),
              lambda out: api.generate_target([NEW], "c", str(out))),
    "gen_python": (lambda out: api.generate_target([OLD], "python", str(out)),
                   lambda out: api.generate_target([NEW], "python", str(out))),
    "pack_over_a_file": (lambda out: api.write_image([OLD], str(out / "x.svm")),
                         lambda out: api.write_image([NEW], str(out / "x.svm"))),
    "pack_into_new_folders": (lambda out: None,
                              lambda out: api.write_image([NEW], str(out / "a" / "b" / "x.svm"))),
}


def snapshot(folder):
    """Every file (bytes) and folder (None) below ``folder``, hidden ones too; None if it is absent."""
    if not folder.exists():
        return None
    return {p.relative_to(folder).as_posix(): (None if p.is_dir() else p.read_bytes()) for p in folder.rglob("*")}


def restore(folder, state):
    shutil.rmtree(folder, ignore_errors=True)
    if state is None:
        return
    folder.mkdir()
    for rel, data in sorted(state.items()):
        if data is None:
            (folder / rel).mkdir()
        else:
            (folder / rel).write_bytes(data)


def compiled_once(monkeypatch):
    """api.compile_model remembering its results: what is under test is the writing, which runs
    a hundred times per scenario."""
    compile_model, done = api.compile_model, {}

    def remembered(inputs, name=None, names=True):
        key = (tuple(inputs), name, names)
        if key not in done:
            done[key] = compile_model(inputs, name=name, names=names)
        return done[key]
    monkeypatch.setattr(api, "compile_model", remembered)


@pytest.fixture(params=sorted(SCENARIOS))
def scenario(request, tmp_path, monkeypatch):
    """(folder, write the new output, old snapshot, new snapshot, operations of a clean run)."""
    compiled_once(monkeypatch)
    make_old, make_new = SCENARIOS[request.param]
    out = tmp_path / "out"
    make_old(out)
    old = snapshot(out)
    with operations(Faults(output.OPS)) as counter:
        make_new(out)
    new = snapshot(out)
    assert old != new and "rename" in counter.seen
    return out, make_new, old, new, counter.seen


def destinations(out, *states):
    """The real paths a message may name: the files and folders of either output, and ``out``."""
    return {str(out)} | {str(out / rel) for state in states if state for rel in state}


@pytest.mark.parametrize("code", [errno.EIO, errno.ENOSPC], ids=["EIO", "ENOSPC"])
def test_the_kth_operation_failing_leaves_the_old_output_or_the_new(scenario, code):
    out, make_new, old, new, seen = scenario
    first_rename = seen.index("rename")
    for k in range(1, len(seen) + 1):
        restore(out, old)
        with operations(Faults(output.OPS, k, fail_with(code))), pytest.raises(api.InputError) as raised:
            make_new(out)
        message, after = str(raised.value), snapshot(out)
        assert "\n" not in message and ".swarmvm-" not in message.split(": ")[0], (k, message)
        assert raised.value.file in destinations(out, old, new) and os.strerror(code) in message, (k, message)
        if seen[k - 1] == "unlink" and k > first_rename + 1 and "written, but" in message:
            # A backup that cannot be deleted after the commit: the new output, and that one
            # backup, named in the message.
            left = {rel: data for rel, data in after.items() if rel not in new}
            assert len(left) == 1 and Path(next(iter(left))).name.startswith(".swarmvm-"), (k, left)
            assert Path(next(iter(left))).name in message and {r: after[r] for r in new} == new
        else:
            assert after == old, (k, seen[k - 1], message)


def test_a_signal_at_the_kth_operation_leaves_the_old_output_or_the_new(scenario):
    """SIGINT at the k-th operation: in staging it ends the write at the next operation and
    nothing stays; in the commit it waits until the commit is done. Either way the
    KeyboardInterrupt comes after, and the folder is one output, whole."""
    out, make_new, old, new, seen = scenario
    first_rename = seen.index("rename")
    for k in range(1, len(seen) + 1):
        restore(out, old)
        with operations(Faults(output.OPS, k, interrupt)), pytest.raises(KeyboardInterrupt):
            make_new(out)
        staging_goes_on = bool(STAGING & set(seen[k:first_rename]))
        assert snapshot(out) == (old if staging_goes_on else new), (k, seen[k - 1])
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_failing_rename_names_the_destination_not_a_temporary_file(tmp_path):
    """What an immutable file (chattr +i, root only) does to a rename, by the seam: the old
    model's files all back, the message naming the file that could not be replaced."""
    out = tmp_path / "out"
    api.generate_target([OLD], "c", str(out))
    old = snapshot(out)
    real = output.OPS

    class Immutable:
        def __getattr__(self, name):
            return getattr(real, name)

        def rename(self, source, destination):
            if Path(destination).name == "swarmvm.c" or Path(source).name == "swarmvm.c":
                raise PermissionError(errno.EPERM, os.strerror(errno.EPERM))
            real.rename(source, destination)
    with operations(Immutable()), pytest.raises(api.InputError) as raised:
        api.generate_target([NEW], "c", str(out))
    assert str(raised.value) == "%s: -o: cannot write (rename: Operation not permitted)" % (out / "swarmvm.c")
    assert snapshot(out) == old


def test_signals_are_not_touched_outside_the_main_thread(tmp_path):
    """From another thread no handler can be installed: the write goes on, whole."""
    import threading
    done = []
    worker = threading.Thread(target=lambda: done.append(api.write_image([NEW], str(tmp_path / "x.svm"))))
    worker.start()
    worker.join()
    assert done and (tmp_path / "x.svm").read_bytes()[:4] == b"SVMI"


# A `swarmvm gen` that pauses at operation argv[1] until the file argv[3] exists, after saying so
# with the file argv[2]: the test sends its signal in between. Only this wrapper, never the
# product, knows about the pause.
PAUSING_GEN = r"""
import os, sys, time
from swarmvm.boundary import output
from swarmvm.cli.commands import main

at, ready, go = int(sys.argv[1]), sys.argv[2], sys.argv[3]
real, seen = output.OPS, []

class Pausing:
    def __getattr__(self, name):
        operation = getattr(real, name)
        def paused(*args):
            seen.append(name)
            if len(seen) == at:
                open(ready, "w").close()
                while not os.path.exists(go):
                    time.sleep(0.01)
            return operation(*args)
        return paused

output.OPS = Pausing()
main(sys.argv[4:], prog_name="swarmvm")
"""


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_real_signal_leaves_the_old_output_or_the_new(signum, tmp_path):
    out = tmp_path / "out"
    api.generate_target([OLD], "c", str(out))
    old = snapshot(out)
    with operations(Faults(output.OPS)) as counter:
        api.generate_target([NEW], "c", str(out))
    new, seen = snapshot(out), counter.seen
    first_rename = seen.index("rename")
    cases = {1: old, seen.index("write", 20) + 1: old, first_rename + 1: new, len(seen): new}
    for k, expected in sorted(cases.items()):
        restore(out, old)
        ready, go = tmp_path / "ready", tmp_path / "go"
        ready.unlink(missing_ok=True)
        go.unlink(missing_ok=True)
        process = subprocess.Popen([sys.executable, "-c", PAUSING_GEN, str(k), str(ready), str(go),
                                    "gen", NEW, "--target", "c", "-o", str(out)],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 60
        while not ready.exists() and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        assert ready.exists(), process.communicate()
        process.send_signal(signum)
        go.touch()
        _, stderr = process.communicate(timeout=60)
        if signum == signal.SIGTERM:
            assert process.returncode == -signal.SIGTERM, (k, stderr)
        else:
            assert process.returncode != 0 and "Traceback" not in stderr, (k, stderr)
        assert snapshot(out) == expected, (k, seen[k - 1])
