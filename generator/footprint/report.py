"""A footprint report: the measured rows with their checks (limits, budgets) and, against a
baseline, their deltas; written as Markdown (a pull-request comment), JUnit XML (CI test
results) or JSON (the next run's baseline). docs/footprint.md describes each.

User text (ELF and file names, supervisor names) reaches Markdown through
:func:`swarmvm.boundary.escape.markdown` and XML through :func:`swarmvm.boundary.escape.html`."""

import json
from dataclasses import dataclass, field

from ..boundary.errors import InputError
from ..boundary.escape import html, markdown
from .budget import Budgets, Check, capacity, checks
from .delta import REPORT_FORMAT, REPORT_VERSION, Baseline, Change, RowDelta, compare, growth, summary
from .measure import COLUMN, COLUMNS, SEED_KPI_SOURCE, Column, Footprint, Limits, Row, row_of, source_sizes
from .symbols import ImageFacts, SizeChange, SymbolDiff, compare_sections, describe, sections_of

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
    facts: dict[str, ImageFacts | None] = field(default_factory=dict)    # by row name: sizes, commit, toolchain
    symbols: int | None = None          # --symbols N: the N largest section and symbol changes of each row
    symbol_diffs: dict[str, SymbolDiff] = field(default_factory=dict)    # by row name, with --symbols

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
          fail_on_growth: float | None = None, symbols: int | None = None) -> FootprintReport:
    """The report of measured images; InputError for two images of the same target and name
    (their rows, budgets and deltas could not be told apart). Each image measured from a file
    has its facts read (symbols.describe); ``symbols``: the N largest section and symbol changes
    of each row in both, InputError when the baseline cannot give a row's sizes."""
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
    facts = {row.name: describe(f) for row, f in zip(rows, ordered)}
    diffs = _symbol_diffs(deltas, baseline, facts, symbols) if symbols is not None else {}
    return FootprintReport(ordered, rows, limits, budgets, checks(rows, limits, budgets), baseline, deltas,
                           fail_on_growth, grown, facts, symbols, diffs)


def _symbol_diffs(deltas: list[RowDelta], baseline: Baseline | None, facts: dict[str, ImageFacts | None],
                  count: int) -> dict[str, SymbolDiff]:
    """Each row in both's ``count`` largest section and symbol changes; InputError (one line, naming
    the baseline's image) when its sizes are not there to compare with: fail closed, never a
    comparison with nothing."""
    if baseline is None:
        raise InputError("", "symbols", "the section and symbol changes are against a baseline: give one")
    diffs = {}
    for delta in deltas:
        if delta.status not in ("changed", "renamed", "unchanged"):
            continue
        old_name = delta.old_name or delta.row.name
        before, why = sections_of(baseline.facts[old_name])
        if before is None:
            raise InputError(baseline.file, baseline.keys[old_name] + ".sections",
                             "--symbols cannot compare %s: %s (write the baseline again with this swarmvm)"
                             % (old_name, why))
        now = facts.get(delta.row.name)
        if now is None or now.sections is None:
            raise InputError(delta.row.name, "", "--symbols: measured in memory, no ELF to read its symbols from")
        diffs[delta.row.name] = compare_sections(before, now.sections, count)
    return diffs


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


def _value(value: int | None, state: str) -> str:
    """A figure's cell: the number, or why there is none (``unknown``, ``not measured``)."""
    return "%d" % value if value is not None else state


def _bound_cells(check: Check | None, value: int | None) -> list[str]:
    """A bound and its margin (the bound less the figure, and that as a per cent of the bound):
    ``none`` without one, ``unknown`` when the figure is."""
    if check is None:
        return ["none", "\u2014"]
    if value is None:
        return ["%d" % check.bound, "unknown"]
    share = " (%.1f %%)" % (100 * (check.bound - value) / check.bound) if check.bound else ""
    return ["%d" % check.bound, "%+d%s" % (check.bound - value, share)]


def _share(value: int | None, whole: int | None) -> str:
    return "unknown" if value is None else "%.1f %%" % (100 * value / whole) if whole else "capacity unknown"


def _capacity_cell(target: str, column: str, before: int | None, after: int | None, compared: bool) -> str:
    """The figure as a share of the robot's own capacity (before -> after against a baseline), or
    ``capacity unknown`` when its target's record gives none."""
    whole, _ = capacity(target, column)
    if whole is None:
        return "capacity unknown"
    if compared and before is not None and before != after:
        return "%s \u2192 %s" % (_share(before, whole), _share(after, whole))
    return _share(after, whole)


def _figures_table(report: FootprintReport, row: Row, delta: RowDelta | None, columns: tuple[Column, ...]) -> list[str]:
    """One row's every figure: before and after (against a baseline), change and per cent, its
    budget and limit each with its margin, and its share of the robot's capacity."""
    compared = report.baseline is not None
    bounds = {(c.column, c.kind): c for c in report.checks if c.row.name == row.name}
    head = ["figure"] + (["before", "after", "\u0394", "%"] if compared else ["value"])
    head += ["budget", "margin", "limit", "margin", "of capacity"]
    lines = ["| %s |" % " | ".join(head), "|---|%s" % ("---:|" * (len(head) - 1))]
    removed = delta is not None and delta.status == "removed"
    for column in columns:
        change = delta.changes.get(column.key) if delta is not None else None
        state = "unknown" if column.key in row.unknown else "not measured"
        after = None if removed else row.values.get(column.key)
        after_cell = "removed" if removed else _value(after, state)
        before: int | None = None
        cells = []
        if compared:
            if removed:
                before = row.values.get(column.key)
                before_cell = _value(before, state)
            elif change is not None:
                before = change.old
                before_cell = _value(before, change.before or "not measured")
            else:
                before_cell = "\u2014"
            cells += [before_cell, after_cell] + _change_cells(change)
        else:
            cells.append(after_cell)
        if removed:
            cells += ["\u2014"] * 5
        else:
            cells += _bound_cells(bounds.get((column.key, "budget")), after)
            cells += _bound_cells(bounds.get((column.key, "limit")), after)
            cells.append(_capacity_cell(row.target, column.key, before, after, compared))
        lines.append("| %s (%s) | %s |" % (markdown(column.key),
                                           markdown(column.unit), " | ".join(cells)))
    return lines


def _change_cells(change: Change | None) -> list[str]:
    """The change of a figure in its unit and per cent; ``\u2014`` where one side has none."""
    if change is None or change.old is None or change.new is None:
        return ["\u2014", "\u2014"]
    if change.old == 0:
        return ["%+d" % change.delta, "from 0" if change.delta else "+0.00 %"]
    return ["%+d" % change.delta, "%+.2f %%" % (100 * change.delta / change.old)]


def _capacity_notes(rows: list[Row], columns: tuple[Column, ...]) -> list[str]:
    """What each target's capacity is, and why a figure has none: said once under the tables."""
    notes = []
    for target in sorted({row.target for row in rows}):
        known: dict[str, int] = {}
        missing: set[str] = set()
        for column in columns:
            whole, what = capacity(target, column.key)
            if whole is None:
                missing.add(what)
            else:
                known[what] = whole
        parts = ["capacity: " + ", ".join("%s %d B" % item for item in sorted(known.items()))] if known else []      # escaped: through markdown() or html() as a whole, where written
        parts += ["capacity unknown: " + why for why in sorted(missing)]      # escaped: through markdown() or html() as a whole, where written
        notes.append("- " + markdown("%s: %s" % (target, "; ".join(parts))))
    return notes


def _figures_section(report: FootprintReport) -> list[str]:
    """Every row's figures with their budgets, margins and capacity shares, one table a row:
    against a baseline the rows that changed open and the rest folded; without one, all folded."""
    blocks: list[tuple[Row, RowDelta | None, bool]]
    if report.baseline is None:
        blocks = [(r, None, False) for r in report.rows]
        columns = _shown(report.rows)
    else:
        blocks = [(d.row, d, d.status != "unchanged") for d in report.deltas]
        columns = tuple(c for c in COLUMNS if c in _shown([d.row for d in report.deltas])
                        or any(c.key in d.changes for d in report.deltas))
    if not blocks:
        return []
    lines = ["", "## Every figure: before and after, budget, limit and margin, share of the robot's capacity"]
    for row, delta, shown in blocks:
        title = row.name + (": %s" % delta.status if delta is not None else "")      # escaped: through markdown() or html() as a whole, where written
        if delta is not None and delta.old_name:
            title += " (was %s)" % delta.old_name      # escaped: through markdown() or html() as a whole, where written
        lines += ["", "<details%s><summary>%s</summary>" % (" open" if shown else "", html(title)), ""]
        lines += _figures_table(report, row, delta, columns) + ["", "</details>"]
    return lines + [""] + _capacity_notes([b[0] for b in blocks], columns)


def _images_section(report: FootprintReport) -> list[str]:
    """Where each image came from: its ELF and digest, the commit, the toolchain, the table image's
    digest (the supervisor as compiled); against a baseline, the baseline's where they differ."""
    described = [(row, facts) for row in report.rows if (facts := report.facts.get(row.name)) is not None]
    if not described:
        return []
    lines = ["", "<details><summary>Where each image came from: ELF, commit, toolchain, supervisor</summary>", "",
             "| row | ELF | ELF sha256 | commit | toolchain | tables sha256 |", "|---|---|---|---|---|---|"]
    renamed = {d.row.name: d.old_name for d in report.deltas if d.old_name}
    for row, facts in described:
        commit = facts.commit.text() if facts.commit is not None else ""
        toolchain = facts.toolchain.text() if facts.toolchain is not None else ""
        old = report.baseline.facts.get(renamed.get(row.name, row.name)) if report.baseline is not None else None
        if old is not None and old.commit is not None and old.commit.text() != commit:
            commit += " (baseline: %s)" % old.commit.text()      # escaped: through markdown() or html() as a whole, where written
        if old is not None and old.toolchain is not None and old.toolchain.text() != toolchain:
            toolchain += " (baseline: %s)" % old.toolchain.text()      # escaped: through markdown() or html() as a whole, where written
        lines.append("| %s |" % " | ".join(markdown(text) for text in (
            row.name, facts.elf, (facts.elf_sha256 or "")[:16], commit, toolchain, (row.tables_sha256 or "")[:16])))
    return lines + ["", "</details>"]


def _size_row(change: SizeChange, symbol: bool) -> str:
    """One section's or symbol's line: its name (a symbol's section too), before, after, change, per cent."""
    names = [change.name, change.section] if symbol else [change.section]
    return "| %s | %s | %s | %+d | %s |" % (" | ".join(markdown(n) for n in names), _value(change.old, "\u2014"),
                                          _value(change.new, "\u2014"), change.delta, markdown(change.percent()))


def _symbols_section(report: FootprintReport) -> list[str]:
    """With ``--symbols N``: each row in both's N largest section changes and N largest symbol
    changes, largest first (as Bloaty's ``-d sections,symbols``), in bytes."""
    if report.symbols is None:
        return []
    lines = ["", "## The %d largest section and symbol changes of each row (bytes)" % report.symbols]
    alone = sorted((d.row.name, d.status) for d in report.deltas if d.row.name not in report.symbol_diffs)
    lines += [""] * bool(alone) + ["- " + markdown("%s: %s, nothing to compare it with" % item) for item in alone]
    for name, diff in sorted(report.symbol_diffs.items()):
        if not diff.sections and not diff.symbols:
            lines += ["", "- " + markdown("%s: no section or symbol changed" % name)]
            continue
        lines += ["", markdown("%s:" % name), "", "| section | before | after | \u0394 | % |", "|---|---:|---:|---:|---:|"]
        lines += [_size_row(change, False) for change in diff.sections]
        lines += ["", "| symbol | section | before | after | \u0394 | % |", "|---|---|---:|---:|---:|---:|"]
        lines += [_size_row(change, True) for change in diff.symbols]
    return lines


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
    lines += _figures_section(report)
    lines += _symbols_section(report)
    lines += _images_section(report)
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
    images = [dict(f.as_json(), budget=report.budgets.of(f.target, f.supervisor),
                   **(facts.as_json() if (facts := report.facts.get(row.name)) is not None else {}))
              for f, row in zip(report.footprints, report.rows)]
    data = dict(format=REPORT_FORMAT, version=REPORT_VERSION, limits=report.limits.as_json(),
                budget_file=report.budgets.file or None, images=images, violations=report.failures())
    if runtime_sizes:
        data.update(source_bytes=source_sizes(), seed_source_bytes=SEED_KPI_SOURCE)
    return json.dumps(data, indent=2) + "\n"
