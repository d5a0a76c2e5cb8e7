"""Footprint deltas: a report compared with a baseline, an earlier JSON report of the same
format version (docs/footprint.md, "Deltas").

Rows are matched by target and supervisor; each column both rows hold gives a :class:`Change`
in its unit and per cent. A row only in the report is new, one only in the baseline removed.
Growth is judged on exact fractions (``100 * delta > percent * old``), so a column that grew by
exactly the allowed per cent passes, and one that grew from 0 grew by more than any."""

import json
from dataclasses import dataclass
from fractions import Fraction

from ..boundary.errors import InputError, decode_text, read_input
from ..boundary.structure import check_structure
from .measure import COLUMN, COLUMNS, Row, column_value

REPORT_FORMAT = "swarmvm footprint"
REPORT_VERSION = 1
STATUS_ORDER = ("changed", "new", "removed", "unchanged")


@dataclass(frozen=True)
class Baseline:
    file: str
    rows: list[Row]


def _image_row(path: str, key: str, image: object) -> Row:
    if not isinstance(image, dict):
        raise InputError(path, key, "must be an object")
    names = []
    for part in ("target", "supervisor"):
        if not isinstance(image.get(part), str):
            raise InputError(path, "%s.%s" % (key, part), "must be a string")
        names.append(image[part])
    values = {}
    for column in COLUMNS:
        value = column_value(image, column)
        if value is None:
            continue                                    # a figure this row was not measured for
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise InputError(path, "%s.%s" % (key, ".".join(column.path)), "must be a whole number, at least 0")
        values[column.key] = value
    return Row(names[0], names[1], values)


def read_baseline(path: str) -> Baseline:
    """The rows of a JSON report written by ``swarmvm footprint --json`` of this format version;
    InputError naming the file and the key for anything else."""
    text = decode_text(path, read_input(path))
    check_structure(path, text)
    try:
        data = json.loads(text)
    except ValueError as exc:                           # JSONDecodeError
        raise InputError(path, "", "not a JSON file (%s)" % exc)
    if not isinstance(data, dict) or data.get("format") != REPORT_FORMAT:
        raise InputError(path, "format", "not a swarmvm footprint report (write one with swarmvm footprint --json)")
    if data.get("version") != REPORT_VERSION:
        raise InputError(path, "version", "a footprint report of version %s; this swarmvm compares with version %d "
                         "(write the baseline again)" % (json.dumps(data.get("version")), REPORT_VERSION))
    images = data.get("images")
    if not isinstance(images, list):
        raise InputError(path, "images", "must be a list")
    rows, seen = [], set()
    for index, image in enumerate(images):
        row = _image_row(path, "images[%d]" % index, image)
        if row.name in seen:
            raise InputError(path, "images[%d]" % index, "a second row %s" % row.name)
        seen.add(row.name)
        rows.append(row)
    return Baseline(path, rows)


@dataclass(frozen=True)
class Change:
    column: str
    old: int
    new: int

    @property
    def delta(self) -> int:
        return self.new - self.old

    def grew_over(self, percent: Fraction) -> bool:
        return self.delta * 100 > percent * self.old

    def text(self) -> str:
        """``+512 B, +5.69 %``; from 0, ``+12 B, from 0``."""
        unit = COLUMN[self.column].unit
        if self.old == 0:
            return "%+d %s, from 0" % (self.delta, unit)
        return "%+d %s, %+.2f %%" % (self.delta, unit, 100 * self.delta / self.old)


@dataclass(frozen=True)
class RowDelta:
    """A row against the baseline: ``row`` is the report's (the baseline's when removed)."""
    row: Row
    status: str
    changes: dict[str, Change]


def compare(rows: list[Row], baseline: Baseline) -> list[RowDelta]:
    """Every row of the report and the baseline: changed, new, removed, then unchanged rows."""
    old = {row.name: row for row in baseline.rows}
    new = {row.name: row for row in rows}
    deltas = []
    for name in sorted(old.keys() | new.keys()):
        if name not in old:
            deltas.append(RowDelta(new[name], "new", {}))
        elif name not in new:
            deltas.append(RowDelta(old[name], "removed", {}))
        else:
            before, after = old[name].values, new[name].values
            changes = {c.key: Change(c.key, before[c.key], after[c.key]) for c in COLUMNS
                       if c.key in before and c.key in after}
            changed = any(change.delta for change in changes.values())
            deltas.append(RowDelta(new[name], "changed" if changed else "unchanged", changes))
    return sorted(deltas, key=lambda d: (STATUS_ORDER.index(d.status), d.row.target, d.row.supervisor))


def _total(deltas: list[RowDelta], column: str) -> str:
    both = [d.changes[column] for d in deltas if column in d.changes]
    return "%s (%s)" % (COLUMN[column].label, Change(column, sum(c.old for c in both), sum(c.new for c in both)).text())


def summary(deltas: list[RowDelta], baseline: Baseline) -> str:
    """One line: how many rows changed, came and went, and the flash and RAM totals' change over
    the rows in both."""
    count = {status: sum(d.status == status for d in deltas) for status in STATUS_ORDER}
    both = count["changed"] + count["unchanged"]
    return "Against %s: %s; in total over the %d row%s in both: %s, %s." % (
        baseline.file, ", ".join("%d %s" % (count[s], s) for s in STATUS_ORDER), both, "" if both == 1 else "s",
        _total(deltas, "flash"), _total(deltas, "ram"))


def growth(deltas: list[RowDelta], percent: float) -> dict[str, str]:
    """Row name -> what grew by more than ``percent`` per cent in it. The float is taken as the
    decimal it was written as (0.3, not 0.29999...), so the boundary is the one the user typed."""
    exact = Fraction(repr(percent))
    found = {}
    for delta in deltas:
        over = [c for c in delta.changes.values() if c.grew_over(exact)]
        if over:
            found[delta.row.name] = "grew by more than %g %%: %s" % (
                percent, ", ".join("%s (%s)" % (c.column, c.text()) for c in over))
    return found
