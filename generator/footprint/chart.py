"""The footprint report as a picture: per row a bar of flash and of static RAM, each split into VM
core, tables and application, and a bar of the worst-case stack and of the worst cycles per step
where they were measured; against a baseline, the baseline's figure as a thin bar above each;
the row's budget (dashed) and limit (solid) marked across its bars; a row over a budget or limit
(or whose figure for one is unknown) marked.

Each target has its own block and its own scale per figure (a Kilobot's 2 KB of SRAM and a
CapBot's 256 KB on one axis would make one of them unreadable). A bar's value is written in a
column of its own right of the bars, where no budget or limit line reaches, so no line strikes a
label through. A self-contained SVG written here, without a plotting library: the same report
gives the same bytes (coordinates rounded to 0.1 px, rows in the report's order), and every name
reaches it through :func:`swarmvm.boundary.escape.html`."""

from dataclasses import dataclass

from ..boundary.escape import html
from .measure import COLUMN, Row
from .report import FootprintReport

PARTS = ("core", "tables", "application")        # the split of the flash and RAM bars
SPLIT = ("flash", "ram")
SINGLE = ("stack", "cycles")                      # one-part bars, drawn when some row has the figure
LABEL_WIDTH, PANEL_WIDTH, VALUE_WIDTH, GAP = 220, 240, 110, 20
TOP, HEADER, ROW_HEIGHT, BEFORE_HEIGHT, BAR_HEIGHT = 76, 26, 34, 6, 16
STYLE = (".core{fill:#4e79a7}.tables{fill:#f28e2b}.application{fill:#bab0ac}.stack{fill:#59a14f}"
         ".cycles{fill:#b07aa1}.before{fill:#d9d9d9;stroke:#7f7f7f;stroke-width:0.5}"
         ".budget{stroke:#d62728;stroke-width:2;stroke-dasharray:4 2}.limit{stroke:#000;stroke-width:2}"
         ".over{fill:#fde0e0}.overlabel{fill:#d62728;font-weight:bold}"
         "text{font-family:sans-serif;font-size:12px}.target{font-weight:bold}")


@dataclass(frozen=True)
class _Line:
    """One row of the chart: the figures now (None for a removed row) and the baseline's (None
    without a baseline, or for a new row)."""
    name: str
    target: str
    now: Row | None
    before: Row | None
    status: str


def _x(panel: int) -> int:
    return LABEL_WIDTH + panel * (PANEL_WIDTH + VALUE_WIDTH + GAP)


def _panels(report: FootprintReport) -> tuple[str, ...]:
    """flash and RAM always; the stack and cycles when some row, now or in the baseline, has them."""
    rows = list(report.rows) + ([r for r in report.baseline.rows] if report.baseline is not None else [])
    return SPLIT + tuple(c for c in SINGLE if any(c in r.values or c in r.unknown for r in rows))


def _lines(report: FootprintReport) -> list[_Line]:
    """The chart's rows by target, in the report's order: each row now beside its baseline row
    (a renamed one's old row), and the removed rows of the baseline."""
    if report.baseline is None:
        return [_Line(r.name, r.target, r, None, "") for r in report.rows]
    old = {r.name: r for r in report.baseline.rows}
    found = [_Line(d.row.name, d.row.target, None if d.status == "removed" else d.row,
                   old.get(d.old_name or d.row.name), d.status) for d in report.deltas]
    return sorted(found, key=lambda line: (line.target, line.name))


def _bounds(report: FootprintReport, name: str, column: str) -> dict[str, int]:
    """{"limit": bound, "budget": bound} of a row's figure, those it has."""
    return {c.kind: c.bound for c in report.checks if c.row.name == name and c.column == column}


def _scales(report: FootprintReport, lines: list[_Line], panels: tuple[str, ...]) -> dict[tuple[str, str], float]:
    """Pixels per unit of each target's panel: its largest figure (now or before), budget or
    limit spans the panel."""
    scales = {}
    for target in sorted({line.target for line in lines}):
        for column in panels:
            figures = [row.values.get(column, 0) for line in lines if line.target == target
                       for row in (line.now, line.before) if row is not None]
            bounds = [b for line in lines if line.target == target for b in _bounds(report, line.name, column).values()]
            scales[(target, column)] = PANEL_WIDTH / max(figures + bounds + [1])
    return scales


def _label(now: Row | None, before: Row | None, column: str) -> str:
    """A bar's value: the figure now, and its change against the baseline (``12756 (+646)``,
    ``unknown (was 145)``, ``removed``); ``unknown`` when measured but not known."""
    if now is None:
        return "removed"
    value = now.values.get(column)
    text = "%d" % value if value is not None else ("unknown" if column in now.unknown else "")
    old = before.values.get(column) if before is not None else None
    if old is not None and value is not None and old != value:
        text += " (%+d)" % (value - old)
    elif old is not None and value is None:
        text += " (was %d)" % old
    return text


def _bar(line: _Line, panel: int, column: str, top: float, scale: float) -> list[str]:
    """The baseline's thin bar (when there is one) above the bar now, split into its parts."""
    x0 = float(_x(panel))
    unit = COLUMN[column].unit
    name = html(line.name)
    found = []
    old = line.before.values.get(column) if line.before is not None else None
    if old is not None:
        found.append('<rect class="before" x="%.1f" y="%.1f" width="%.1f" height="%d"><title>%s %s before: %d %s</title>'
                     '</rect>' % (x0, top, old * scale, BEFORE_HEIGHT, name, column, old, unit))      # escaped: a column key, part and unit of the package (COLUMNS, PARTS)
    if line.now is None:
        return found
    x = x0
    for part in (PARTS if column in SPLIT else (column,)):
        value = line.now.values.get(column if part == column else "%s_%s" % (column, part))   # escaped: a column key
        if value is None:
            continue
        found.append('<rect class="%s" x="%.1f" y="%.1f" width="%.1f" height="%d"><title>%s %s: %s, %d %s</title></rect>'
                     % (part, x, top + BEFORE_HEIGHT + 2, value * scale, BAR_HEIGHT, name, column, part, value, unit))      # escaped: a column key, part and unit of the package (COLUMNS, PARTS)
        x += value * scale
    return found


def _row(report: FootprintReport, line: _Line, top: float, panels: tuple[str, ...],
         scales: dict[tuple[str, str], float]) -> list[str]:
    name = html(line.name)
    failed = [c for c in report.checks if c.row.name == line.name and c.status == "failed"] if line.now else []
    base = top + BEFORE_HEIGHT + 2 + BAR_HEIGHT - 3           # the text baseline of the bar now
    lines = ['<g class="row" data-row="%s"%s>' % (name, ' data-over="true"' if failed else "")]
    if failed:
        lines.append('<rect class="over" x="0" y="%.1f" width="%d" height="%d"><title>%s</title></rect>'
                     % (top - 2, _x(len(panels)), ROW_HEIGHT - 4, html("; ".join(c.message for c in failed))))
    lines.append('<text x="4" y="%.1f">%s</text>' % (base, name))
    if failed:
        lines.append('<text class="overlabel" x="4" y="%.1f">over %s</text>'
                     % (base - BAR_HEIGHT + 2, " and ".join(html(kind) for kind in sorted({c.kind for c in failed}))))
    for panel, column in enumerate(panels):
        scale = scales[(line.target, column)]
        lines += _bar(line, panel, column, top, scale)
        over = any(c.column == column for c in failed)
        lines.append('<text%s x="%.1f" y="%.1f">%s</text>' % (' class="overlabel"' if over else "",
                                                              _x(panel) + PANEL_WIDTH + 6, base,
                                                              html(_label(line.now, line.before, column))))
        if line.now is None:
            continue
        for kind, bound in sorted(_bounds(report, line.name, column).items()):
            at = _x(panel) + bound * scale
            title = "%s %s: %d %s" % (COLUMN[column].label, kind, bound,
                                      COLUMN[column].unit)      # escaped: the package's own unit (COLUMNS)
            lines.append('<line class="%s" x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f"><title>%s</title></line>'
                         % (kind, at, top - 1, at, top + ROW_HEIGHT - 6, title))
    return lines + ["</g>"]


def svg_chart(report: FootprintReport) -> str:
    """The chart of a report as SVG text."""
    panels = _panels(report)
    lines_of = _lines(report)
    scales = _scales(report, lines_of, panels)
    targets = sorted({line.target for line in lines_of})
    width = _x(len(panels)) - GAP + 10
    height = TOP + len(targets) * HEADER + len(lines_of) * ROW_HEIGHT + 10
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">'
             % (width, height, width, height),
             "<title>VM footprint</title>", "<style>%s</style>" % STYLE]
    for panel, column in enumerate(panels):
        lines.append('<text x="%d" y="18">%s (%s)</text>' % (_x(panel), COLUMN[column].label,
                                                             COLUMN[column].unit))      # escaped: the package's own unit
    legend = [(part, "VM core" if part == "core" else part) for part in PARTS + tuple(c for c in SINGLE if c in panels)]
    if report.baseline is not None:
        legend.append(("before", "baseline"))
    for index, (part, label) in enumerate(legend):
        lines.append('<rect class="%s" x="%d" y="30" width="12" height="12"/><text x="%d" y="40">%s</text>'
                     % (part, LABEL_WIDTH + index * 100, LABEL_WIDTH + index * 100 + 16, label))
    at = LABEL_WIDTH + len(legend) * 100
    lines.append('<line class="budget" x1="%d" y1="36" x2="%d" y2="36"/><text x="%d" y="40">budget</text>'
                 % (at, at + 20, at + 24))
    lines.append('<line class="limit" x1="%d" y1="36" x2="%d" y2="36"/><text x="%d" y="40">limit</text>'
                 % (at + 80, at + 100, at + 104))
    lines.append('<rect class="over" x="%d" y="30" width="12" height="12"/><text class="overlabel" x="%d" y="40">'
                 'over a budget or limit</text>' % (at + 150, at + 166))
    top = float(TOP)
    for target in targets:
        lines.append('<text class="target" x="4" y="%.1f">%s (its own scale)</text>' % (top + 14, html(target)))
        top += HEADER
        for line in (entry for entry in lines_of if entry.target == target):
            lines += _row(report, line, top, panels, scales)
            top += ROW_HEIGHT
    return "\n".join(lines + ["</svg>"]) + "\n"
