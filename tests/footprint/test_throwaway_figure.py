"""A new footprint figure is one Column in swarmvm.footprint.measure.COLUMNS and the measurement
that writes it into the image's JSON (docs/extending.md): a throwaway figure added so shows in
the table, is budgeted, compared with a baseline and judged for growth like the others, without
another change to budgets, deltas or the report."""

import json

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.footprint import budget, delta, measure, report
from swarmvm.footprint.measure import Column, Footprint, Split

FIGURE = Column("symbols", "symbols", ("symbols",), "symbols")


@pytest.fixture
def with_figure(monkeypatch):
    """The figure appended to COLUMNS (the modules that read the list, as its import gave them it)
    and written by every Footprint's as_json, as a measurement filling a field would."""
    columns = measure.COLUMNS + (FIGURE,)
    for module in (measure, delta, report):
        monkeypatch.setattr(module, "COLUMNS", columns)
    monkeypatch.setitem(measure.COLUMN, FIGURE.key, FIGURE)
    plain = Footprint.as_json
    monkeypatch.setattr(Footprint, "as_json", lambda self: dict(plain(self), symbols=self.symbols))


def footprint(symbols: int) -> Footprint:
    """A measured row whose throwaway figure is ``symbols`` (the field a measurement would fill)."""
    measured = Footprint("kilobot", "energy_worker", "energy_worker.elf", Split(100, 40, 30, 30), Split(50, 20, 0, 30))
    measured.symbols = symbols
    return measured


def test_a_throwaway_figure_is_shown_budgeted_and_compared(with_figure, tmp_path):
    budgets = budget.parse_budgets("budget.toml", {"kilobot": {"symbols": 25}})
    now = report.build([footprint(30)], measure.Limits(), budgets)
    assert "| symbols |" in report.markdown_report(now).splitlines()[4]
    assert now.failures() == ["kilobot/energy_worker: symbols 30 symbols over its budget of 25 symbols (by 5 symbols)"]
    baseline = tmp_path / "baseline.json"
    baseline.write_text(report.json_report(report.build([footprint(20)], measure.Limits(), budget.Budgets())))
    assert json.loads(baseline.read_text())["images"][0]["symbols"] == 20
    compared = report.build([footprint(30)], measure.Limits(), budget.Budgets(), delta.read_baseline(str(baseline)),
                            fail_on_growth=10)
    assert compared.deltas[0].changes["symbols"].text() == "+10 symbols, +50.00 %"
    assert compared.failures() == ["kilobot/energy_worker: grew by more than 10 %: symbols (+10 symbols, +50.00 %)"]


def test_without_the_column_the_figure_is_an_unknown_budget_key():
    with pytest.raises(InputError, match="unknown column"):
        budget.parse_budgets("budget.toml", {"kilobot": {"symbols": 25}})
