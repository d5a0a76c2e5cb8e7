"""The studies write through the output layer (issue 37, point 2): a figure, a summary and a
sweep's trial tables are drawn in memory and written by swarmvm.boundary.output.write_outputs,
so a new file's mode comes from the umask, a failed write leaves nothing partial, and a link or
an input in a destination's place is refused in one line. (The studies' other file accesses —
ARGoS's scratch files, the plugin's build cache — are listed and justified in
tests/layers/test_file_access.py.)"""

import os

import pytest

from swarmvm.boundary import output
from swarmvm.boundary.errors import InputError

pytest.importorskip("matplotlib")
pytest.importorskip("pandas")
pytest.importorskip("pyarrow")


def _figure():
    from swarmvm.studies.plotting import pyplot
    plt = pyplot()
    figure, axis = plt.subplots()
    axis.plot([0, 1], [0, 1])
    axis.set_title("a figure")
    return figure


def test_a_figure_is_written_with_the_umask_and_read_back(tmp_path):
    from swarmvm.studies.plotting import read_encodings, save
    old = os.umask(0o077)
    try:
        path = save(_figure(), tmp_path / "figure.png", "the caption")
    finally:
        os.umask(old)
    assert path.stat().st_mode & 0o777 == 0o600
    assert read_encodings(path)["Description"] == "the caption"


def test_a_figure_over_a_link_is_refused_and_the_link_kept(tmp_path):
    from swarmvm.studies.plotting import save
    target = tmp_path / "elsewhere.png"
    target.write_bytes(b"precious")
    (tmp_path / "figure.png").symlink_to(target)
    with pytest.raises(InputError, match="is a symbolic link"):
        save(_figure(), tmp_path / "figure.png", "caption")
    assert target.read_bytes() == b"precious"


class _FailingWrites(output.FileOps):
    def write(self, fd, data):
        raise OSError(28, "No space left on device")


def test_a_failed_write_leaves_no_partial_figure_or_table(tmp_path, monkeypatch):
    from swarmvm.studies.plotting import save
    from swarmvm.studies.sweeps import done_keys, write_trial
    monkeypatch.setattr(output, "OPS", _FailingWrites())
    with pytest.raises(InputError, match="No space left on device"):
        save(_figure(), tmp_path / "figure.png", "caption")
    with pytest.raises(InputError, match="No space left on device"):
        write_trial(tmp_path / "sweep", "k1", {"trials": [{"a": 1}], "other": [{"b": 2}]}, ["other", "trials"])
    assert not (tmp_path / "figure.png").exists() and done_keys(tmp_path / "sweep") == set()
    assert [p for p in tmp_path.rglob("*") if p.is_file()] == []
    monkeypatch.undo()
    write_trial(tmp_path / "sweep", "k1", {"trials": [{"a": 1}], "other": [{"b": 2}]}, ["other", "trials"])
    assert done_keys(tmp_path / "sweep") == {"k1"}
