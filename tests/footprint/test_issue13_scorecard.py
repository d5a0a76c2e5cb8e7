"""benchmarks/issue13.py judges each target of issue 13 from the benchmarks' JSON files: a
figure past its target is met, one short of it is not, a missing file is "not measured"."""

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def scorecard(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))    # as when run: its folder is on the path
    spec = importlib.util.spec_from_file_location("issue13", ROOT / "benchmarks" / "issue13.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    monkeypatch.setattr(module, "BUILD", tmp_path)
    (tmp_path / "bench").mkdir()
    return module


def write(folder: Path, name: str, content) -> None:
    (folder / name).write_text(json.dumps(content))


def by_item(rows):
    return {r["item"]: r for r in rows}


def test_each_target_is_judged_on_its_worst_supervisor(scorecard, tmp_path):
    write(tmp_path, "bench/python_vs_baseline.json", {"rows": [
        dict(supervisor="a", steps=4.0, steps_baseline=1.0, loads=6.0, loads_baseline=1.0),
        dict(supervisor="b", steps=1.9, steps_baseline=1.0, loads=5.0, loads_baseline=1.0)]})
    write(tmp_path, "footprint.json", {"images": [
        dict(target="kilobot", supervisor="a", flash=dict(core=4096)),
        dict(target="kilobot", supervisor="b", flash=dict(core=3000)),
        dict(target="capbot", supervisor="a", flash=dict(core=3073))]})
    rows = by_item(scorecard.targets())
    assert rows["1. Python VM steps"]["met"] is False and "(b)" in rows["1. Python VM steps"]["measured"]
    assert rows["4. Python image load"]["met"] is True
    assert rows["3. Kilobot core flash, as built (make footprint)"]["met"] is True
    assert rows["3. Kilobot core flash, as built (make footprint)"]["measured"] == "4,096 B (a)"
    assert rows["3. CapBot core flash (make footprint)"]["met"] is False
    assert rows["2. C++ VM steps"] == dict(item="2. C++ VM steps", target=">= 2x on every supervisor",
                                           measured="not measured", met=None)


def test_the_summary_line_names_what_is_not_met(scorecard, tmp_path, capsys, monkeypatch):
    write(tmp_path, "bench/cpp_steps.json", {"rows": [dict(supervisor="x", ratio=1.5)]})
    monkeypatch.setattr("sys.argv", ["issue13.py", "--json", str(tmp_path / "out.json")])
    scorecard.main()
    last = capsys.readouterr().out.splitlines()[-1]
    assert last.startswith("issue 13: 0 of 1 measured targets met; NOT met: 2. C++ VM steps; not measured: ")
    assert json.loads((tmp_path / "out.json").read_text())[1]["met"] is False
