"""A footprint report: the measured rows with their checks (limits, budgets) and, against a
baseline, their deltas; written as Markdown (a pull-request comment), JUnit XML (CI test
results) or JSON (the next run's baseline). docs/footprint.md describes each.

User text (ELF and file names, supervisor names) reaches Markdown through
:func:`swarmvm.boundary.escape.markdown` and XML through :func:`swarmvm.boundary.escape.html`."""

import json
from dataclasses import dataclass

from ..boundary.errors import InputError
from ..boundary.escape import html, markdown
from .budget import Budgets, Check, checks
from .delta import REPORT_FORMAT, REPORT_VERSION, Baseline, RowDelta, compare, growth, summary
from .measure import COLUMN, COLUMNS, SEED_KPI_SOURCE, Column, Footprint, Limits, Row, row_of, source_sizes

INTRODUCTION = ("Bytes in the linked images. "
                "Flash = code + constants + .data initialisers; RAM = .data + .bss (static, no stack); "
                "stack = worst case of the whole program, VM step stack = of svm_step and what it calls.")


@dataclass(frozen=True)
class FootprintReport:
    footprints: list[Footprint]         # sorted by target, then supervisor
    rows: list[Row]                     # the same order
    limits: Limits
    budgets: Budgets
    checks: list[Check]
    baseline: Baseline | None
    deltas: list[RowDelta]              # empty without a baseline
    fail_on_growth: float | None
    grown: dict[str, str]               # row name -> what grew past fail_on_growth

    def failures(self) -> list[str]:
        """One line per row over a limit or budget (or whose figure for one is unknown), or
        grown past ``fail_on_growth`` (or whose change it cannot judge)."""
        problems: dict[str, list[str]] = {}
        for check in self.checks:
            if not check.passed:
                problems.setdefault(check.row.name, []).append(check.message)
        for name, text in self.grown.items():
            problems.setdefault(name, []).append(text)
        return ["%s: %s" % (name, "; ".join(texts)) for name, texts in sorted(problems.items())]


def build(footprints: list[Footprint], limits: Limits, budgets: Budgets, baseline: Baseline | None = None,
          fail_on_growth: float | None = None) -> FootprintReport:
    """The report of measured images; InputError for two images of the same target and name
    (their rows, budgets and deltas could not be told apart)."""
    ordered = sorted(footprints, key=lambda f: (f.target, f.supervisor))
    for first, second in zip(ordered, ordered[1:]):
        if (first.target, first.supervisor) == (second.target, second.supervisor):
            raise InputError(second.elf, "", "a second %s image named %s (the first: %s)"
                             % (second.target, second.supervisor, first.elf))
    rows = [row_of(f) for f in ordered]
    budgets.check_rows({(row.target, row.supervisor) for row in rows})
    now = {row.name: budgets.of(row.target, row.supervisor) for row in rows}
    deltas = compare(rows, baseline, now) if baseline is not None else []
    grown = growth(deltas, fail_on_growth, baseline) if fail_on_growth is not None else {}
    return FootprintReport(ordered, rows, limits, budgets, checks(rows, limits, budgets), baseline, deltas,
                           fail_on_growth, grown)


def _shown(rows: list[Row]) -> tuple[Column, ...]:
    """The columns some row has a figure, or an unknown one, for: the cycles only when measured."""
    return tuple(c for c in COLUMNS if any(c.key in r.values or c.key in r.unknown for r in rows))


def _cells(row: Row, columns: tuple[Column, ...], delta: RowDelta | None = None) -> list[str]:
    """A row's figures, each with its change when it changed."""
    cells = []
    for column in columns:
        value = row.values.get(column.key)
        change = delta.changes.get(column.key) if delta is not None else None
        if value is not None:
            cell = str(value)
        elif column.key in row.unknown:
            cell = "unknown"
        else:
            cell = "not measured" if change is not None and change.old is not None else ""
        if change is not None and change.delta:
            cell += " (was %d: %s)" % (change.old or 0, change.text())          # before -> after, delta, per cent
        elif change is not None and (change.old is None) != (change.new is None):
            cell += " (%s)" % change.text()
        if change is not None and change.problem and change.old is not None and change.new is not None:
            cell += " (another event script)"
        cells.append(cell)
    return cells


def _table(rows: list[tuple[list[str], list[str]]], columns: tuple[Column, ...], status: bool) -> list[str]:
    """A Markdown table of (name cells, figure cells); names escaped here."""
    head = ["target", "supervisor"] + (["change"] if status else [])
    lines = ["| %s | %s |" % (" | ".join(head), " | ".join(c.label for c in columns)),
             "|%s%s" % ("---|" * len(head), "---:|" * len(columns))]
    for names, figures in rows:
        lines.append("| %s |" % " | ".join([markdown(n) for n in names] + figures))
    return lines


def _rows_section(report: FootprintReport) -> list[str]:
    """Today's table; against a baseline, a status column and each change, changed rows first
    and the unchanged ones folded in a <details> block."""
    if report.baseline is None:
        columns = _shown(report.rows)
        return _table([([r.target, r.supervisor], _cells(r, columns)) for r in report.rows], columns, status=False)
    columns = tuple(c for c in COLUMNS if c in _shown([d.row for d in report.deltas])
                    or any(c.key in d.changes for d in report.deltas))     # a figure no longer measured, too
    shown = [d for d in report.deltas if d.status != "unchanged"]
    folded = [d for d in report.deltas if d.status == "unchanged"]
    lines = [markdown(summary(report.deltas, report.baseline)), ""]
    if shown:
        lines += _table([([d.row.target, d.row.supervisor + (" (was %s)" % d.old_name.partition("/")[2]
                                                             if d.old_name else ""), d.status],
                          _cells(d.row, columns, d)) for d in shown], columns, status=True)
    if folded:
        lines += ["", "<details><summary>%d unchanged row%s</summary>" % (len(folded), "" if len(folded) == 1 else "s"),
                  ""]
        lines += _table([([d.row.target, d.row.supervisor, d.status], _cells(d.row, columns)) for d in folded],
                        columns, status=True)
        lines += ["", "</details>"]
    return lines


def _cycles_section(report: FootprintReport) -> list[str]:
    """Per row run with an event script: its steps and the worst one, with the inputs it had."""
    measured = [f for f in report.footprints if f.cycles is not None]
    if not measured:
        return []
    lines = ["", "Cycles per step (the image run with the event script: Kilobot CPU cycles in simavr, CapBot "
             "instructions in QEMU):", ""]
    for footprint in measured:
        cycles = footprint.cycles
        assert cycles is not None
        lines.append("- " + markdown("%s/%s: %s, %d steps: mean %d, worst %d at step %d (inputs: %s)"
                                     % (footprint.target, footprint.supervisor, cycles.script, len(cycles.per_step),
                                        cycles.mean, cycles.worst, cycles.worst_step,
                                        " ".join(cycles.worst_inputs) or "none")))
    return lines


def _checks_section(report: FootprintReport) -> list[str]:
    """Every limit and budget of every row, passed or not, with its figure, bound and margin (the
    bound less the figure; negative when over), folded: what a reviewer weighs a change against."""
    if not report.checks:
        return []
    failed = sum(c.status == "failed" for c in report.checks)
    lines = ["", "<details><summary>%d checks, %d failed: figure, bound and margin of each</summary>"
             % (len(report.checks), failed), "", "| check | row | figure | bound | margin | result |",
             "|---|---|---:|---:|---:|---|"]
    for check in report.checks:
        unit = COLUMN[check.column].unit
        value = check.value
        figure = "%d %s" % (value, unit) if value is not None else ("unknown" if check.column in check.row.unknown
                                                                   else "not measured")
        margin = "%+d %s (%.1f %%)" % (check.bound - value, unit, 100 * (check.bound - value) / check.bound) \
            if value is not None and check.bound else ""
        lines.append("| %s | %s | %s | %d %s | %s | %s |" % (
            markdown("%s (%s)" % (check.column, check.kind)), markdown(check.row.name),
            figure, check.bound, unit, margin, check.status))
    return lines + ["", "</details>"]


def _budget_change(column: str, old: int | None, new: int | None) -> str:
    """``ram from 300 to 400 B (loosened)``: a budget against the baseline's (None: there was none)."""
    unit = COLUMN[column].unit
    if new is None:
        return "%s from %d %s to none (removed)" % (column, old or 0, unit)
    if old is None:
        return "%s from none to %d %s (added)" % (column, new, unit)
    return "%s from %d to %d %s (%s)" % (column, old, new, unit, "loosened" if new > old else "tightened")


def markdown_report(report: FootprintReport, runtime_sizes: bool = False) -> str:
    """The report as Markdown; ``runtime_sizes`` adds the runtimes' source sizes (the project's
    own figures, next to the seed's KPI table)."""
    limits = report.limits
    lines = ["# VM footprint", "", INTRODUCTION, ""] + _rows_section(report)
    robots = ["%s flash <= %d B, %s stack >= %d B of %d B SRAM" % (r.robot, r.flash, r.robot, r.min_stack, r.sram)
              for r in limits.robots.values()]
    lines += ["", "Limits: %s." % ", ".join(robots + ["VM <= %d B (seed KPI)" % limits.vm])]
    if report.budgets.file:
        budgeted = sum(check.kind == "budget" for check in report.checks)
        lines += ["", markdown("Budgets: %d checks from %s." % (budgeted, report.budgets.file))]
    changed = ["%s: %s" % (d.row.name, ", ".join(_budget_change(column, old, new) for column, (old, new)
                                                 in d.budgets.items())) for d in report.deltas if d.budgets]
    if changed:
        lines += ["", "Budgets changed against the baseline (shown, not failed: the budget file is part of the "
                  "change under review):", ""] + ["- " + markdown(c) for c in changed]
    lines += _checks_section(report)
    skipped = ["%s: %s" % (c.row.name, c.message) for c in report.checks if c.status == "skipped"]
    if skipped:
        lines += ["", "Not checked:", ""] + ["- " + markdown(s) for s in skipped]
    if report.fail_on_growth is not None:
        lines += ["", "Growth allowed: %g %% per column." % report.fail_on_growth]
    lines += _cycles_section(report)
    unknown = ["%s: %s: unknown: %s" % (row.name, key, why) for row in report.rows for key, why in sorted(row.unknown.items())]
    if unknown:
        lines += ["", "Stack bounds not known:", ""] + ["- " + markdown(u) for u in unknown]
    failures = report.failures()
    if failures:
        lines += ["", "**Failed:**", ""] + ["- " + markdown(failure) for failure in failures]
    if runtime_sizes:
        lines += ["", "## Source size (the seed's KPI table counts bytes of source)", "", "| VM | bytes |", "|---|---:|"]
        lines += ["| %s | %d |" % (name, size) for name, size in {**source_sizes(), **SEED_KPI_SOURCE}.items()]
    return "\n".join(lines) + "\n"


def _testcases(report: FootprintReport) -> list[tuple[str, str, str, str | None]]:
    """(classname, name, failure type, failure message or None) of each check and, with
    ``fail_on_growth``, of each row's growth."""
    cases: list[tuple[str, str, str, str | None]] = [
        (c.row.name, c.title, "skipped" if c.status == "skipped" else c.kind, None if c.passed and c.status != "skipped"
         else c.message) for c in report.checks]
    if report.fail_on_growth is not None:
        title = "growth <= %g %% per column" % report.fail_on_growth
        cases += [(d.row.name, title, "growth", report.grown.get(d.row.name)) for d in report.deltas
                  if d.changes or d.row.name in report.grown]
        if report.baseline is not None and report.baseline.file in report.grown:
            cases.append((report.baseline.file, title, "growth", report.grown[report.baseline.file]))
    return cases


def junit_report(report: FootprintReport) -> str:
    """The checks as JUnit XML: a test case per row and limit, budget (and growth bound), a
    failure element in each one exceeded, so CI systems show them as failed tests."""
    cases = _testcases(report)
    skipped = sum(kind == "skipped" for _, _, kind, _ in cases)
    failed = sum(message is not None and kind != "skipped" for _, _, kind, message in cases)
    counts = 'tests="%d" failures="%d"' % (len(cases), failed)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<testsuites name="swarmvm footprint" %s>' % counts,
             '  <testsuite name="swarmvm footprint" %s errors="0" skipped="%d">' % (counts, skipped)]
    for classname, name, kind, message in cases:
        opening = '    <testcase classname="%s" name="%s"' % (html(classname), html(name))
        if message is None:
            lines.append(opening + "/>")
        elif kind == "skipped":
            lines += [opening + ">", '      <skipped message="%s"/>' % html(message), "    </testcase>"]
        else:
            lines += [opening + ">", '      <failure type="%s" message="%s">%s</failure>'
                      % (kind, html(message), html("%s: %s" % (classname, message))), "    </testcase>"]
    lines += ["  </testsuite>", "</testsuites>"]
    return "\n".join(lines) + "\n"


def json_report(report: FootprintReport, runtime_sizes: bool = False) -> str:
    """The report as JSON, of format ``REPORT_VERSION``: what ``--baseline`` reads next time."""
    images = [dict(f.as_json(), budget=report.budgets.of(f.target, f.supervisor)) for f in report.footprints]
    data = dict(format=REPORT_FORMAT, version=REPORT_VERSION, limits=report.limits.as_json(),
                budget_file=report.budgets.file or None, images=images, violations=report.failures())
    if runtime_sizes:
        data.update(source_bytes=source_sizes(), seed_source_bytes=SEED_KPI_SOURCE)
    return json.dumps(data, indent=2) + "\n"
