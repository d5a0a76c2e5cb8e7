"""The footprint report as a picture: flash and static RAM per row, each bar split into VM core,
tables and application, with the row's budget (dashed) and limit (solid) marked across it.

A self-contained SVG written here, without a plotting library: the same report gives the same
bytes (coordinates rounded to 0.1 px, rows in the report's order), and every name reaches it
through :func:`swarmvm.boundary.escape.html`."""

from ..boundary.escape import html
from .measure import COLUMN
from .report import FootprintReport

PANELS = ("flash", "ram")                       # one panel per total, its split drawn inside
PARTS = ("core", "tables", "application")
LABEL_WIDTH, PANEL_WIDTH, GAP = 220, 320, 40
TOP, ROW_HEIGHT, BAR_HEIGHT = 60, 28, 16
LABEL_CHAR = 7.5                                # px per digit of a 12 px label, at most
STYLE = (".core{fill:#4e79a7}.tables{fill:#f28e2b}.application{fill:#bab0ac}"
         ".budget{stroke:#d62728;stroke-width:2;stroke-dasharray:4 2}.limit{stroke:#000;stroke-width:2}"
         "text{font-family:sans-serif;font-size:12px}")


def _x(panel: int) -> int:
    return LABEL_WIDTH + panel * (PANEL_WIDTH + GAP)


def _bounds(report: FootprintReport, name: str, column: str) -> dict[str, int]:
    """{"limit": bytes, "budget": bytes} of a row's total, those it has."""
    return {c.kind: c.bound for c in report.checks if c.row.name == name and c.column == column}


def _scale(report: FootprintReport, column: str) -> float:
    """Pixels per byte of a panel: its largest total, budget or limit spans the panel."""
    largest = max([row.values[column] for row in report.rows]
                  + [bound for row in report.rows for bound in _bounds(report, row.name, column).values()] + [1])
    return PANEL_WIDTH / largest


def _row(report: FootprintReport, index: int, scales: list[float]) -> list[str]:
    row = report.rows[index]
    top = TOP + index * ROW_HEIGHT
    name = html(row.name)
    lines = ['<g class="row" data-row="%s">' % name,
             '<text x="4" y="%.1f">%s</text>' % (top + BAR_HEIGHT - 3, name)]
    for panel, column in enumerate(PANELS):
        x = float(_x(panel))
        for part in PARTS:
            value = row.values["%s_%s" % (column, part)]
            width = value * scales[panel]
            lines.append('<rect class="%s" x="%.1f" y="%d" width="%.1f" height="%d"><title>%s %s: %s, %d B</title></rect>'
                         % (part, x, top, width, BAR_HEIGHT, name, COLUMN[column].label, part, value))
            x += width
        label = x + 4
        for at in sorted(_x(panel) + bound * scales[panel] for bound in _bounds(report, row.name, column).values()):
            if label - 2 <= at <= label + LABEL_CHAR * len(str(row.values[column])):
                label = at + 4                  # a budget or limit line would strike the label through
        lines.append('<text x="%.1f" y="%.1f">%d</text>' % (label, top + BAR_HEIGHT - 3, row.values[column]))
        for kind, bound in sorted(_bounds(report, row.name, column).items()):
            at = _x(panel) + bound * scales[panel]
            lines.append('<line class="%s" x1="%.1f" y1="%d" x2="%.1f" y2="%d"><title>%s %s: %d B</title></line>'
                         % (kind, at, top - 3, at, top + BAR_HEIGHT + 3, COLUMN[column].label, kind, bound))
    return lines + ["</g>"]


def svg_chart(report: FootprintReport) -> str:
    """The chart of a report as SVG text."""
    width = _x(len(PANELS)) - GAP + 60
    height = TOP + len(report.rows) * ROW_HEIGHT + 10
    scales = [_scale(report, column) for column in PANELS]
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">'
             % (width, height, width, height),
             "<title>VM footprint</title>", "<style>%s</style>" % STYLE]
    for panel, column in enumerate(PANELS):
        lines.append('<text x="%d" y="18">%s (bytes)</text>' % (_x(panel), COLUMN[column].label))
    legend = [(part, "VM core" if part == "core" else part) for part in PARTS]
    for index, (part, label) in enumerate(legend):
        lines.append('<rect class="%s" x="%d" y="30" width="12" height="12"/><text x="%d" y="40">%s</text>'
                     % (part, LABEL_WIDTH + index * 110, LABEL_WIDTH + index * 110 + 16, label))
    at = LABEL_WIDTH + len(legend) * 110
    lines.append('<line class="budget" x1="%d" y1="36" x2="%d" y2="36"/><text x="%d" y="40">budget</text>'
                 % (at, at + 20, at + 24))
    lines.append('<line class="limit" x1="%d" y1="36" x2="%d" y2="36"/><text x="%d" y="40">limit</text>'
                 % (at + 80, at + 100, at + 104))
    for index in range(len(report.rows)):
        lines += _row(report, index, scales)
    return "\n".join(lines + ["</svg>"]) + "\n"
