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
from .measure import COLUMNS, SEED_KPI_SOURCE, Column, Footprint, Limits, Row, row_of, source_sizes

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
        """One line per row over a limit or budget, or grown past ``fail_on_growth``."""
        problems: dict[str, list[str]] = {}
        for check in self.checks:
            if not check.passed:
                problems.setdefault(check.row.name, []).append(check.failure)
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
    deltas = compare(rows, baseline) if baseline is not None else []
    grown = growth(deltas, fail_on_growth) if fail_on_growth is not None else {}
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
        cell = ("unknown" if column.key in row.unknown else "") if value is None else str(value)
        change = delta.changes.get(column.key) if delta is not None else None
        if change is not None and change.delta:
            cell += " (%s)" % change.text()
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
    columns = _shown([d.row for d in report.deltas])
    shown = [d for d in report.deltas if d.status != "unchanged"]
    folded = [d for d in report.deltas if d.status == "unchanged"]
    lines = [markdown(summary(report.deltas, report.baseline)), ""]
    if shown:
        lines += _table([([d.row.target, d.row.supervisor, d.status], _cells(d.row, columns, d)) for d in shown],
                        columns, status=True)
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
        (c.row.name, c.title, c.kind, None if c.passed else c.failure) for c in report.checks]
    if report.fail_on_growth is not None:
        cases += [(d.row.name, "growth <= %g %% per column" % report.fail_on_growth, "growth",
                   report.grown.get(d.row.name)) for d in report.deltas if d.changes]
    return cases


def junit_report(report: FootprintReport) -> str:
    """The checks as JUnit XML: a test case per row and limit, budget (and growth bound), a
    failure element in each one exceeded, so CI systems show them as failed tests."""
    cases = _testcases(report)
    failed = sum(message is not None for _, _, _, message in cases)
    counts = 'tests="%d" failures="%d"' % (len(cases), failed)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<testsuites name="swarmvm footprint" %s>' % counts,
             '  <testsuite name="swarmvm footprint" %s errors="0" skipped="0">' % counts]
    for classname, name, kind, message in cases:
        opening = '    <testcase classname="%s" name="%s"' % (html(classname), html(name))
        if message is None:
            lines.append(opening + "/>")
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
