"""Footprint deltas: a report compared with a baseline, an earlier JSON report of the same
format version (docs/footprint.md, "Deltas").

Rows are matched by target and supervisor, and a row only in the report with one only in the
baseline of the same target and the same table image (its digest) as the one renamed; each
column either row holds gives a :class:`Change` in its unit and per cent. A row only in the
report is new, one only in the baseline removed. Growth is judged on exact fractions
(``100 * delta > percent * old``), so a column that grew by exactly the allowed per cent passes,
and one that grew from 0 grew by more than any.

The delta gate (``--fail-on-growth``) fails closed: besides growth it fails on whatever it cannot
judge, each saying why: a figure that became unknown or is no longer measured (or the reverse),
cycles measured with another event script, a new row beside a removed one of its target (a
rename the digests do not confirm), and a comparison in which no row is in both. A baseline of
other targets only is refused outright, before anything is measured against it."""

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, cast

from ..boundary.errors import InputError
from ..boundary.structure import read_json_document
from .measure import COLUMN, COLUMNS, Row, column_value
from .symbols import ImageFacts, baseline_facts

REPORT_FORMAT = "swarmvm footprint"
REPORT_VERSION = 1
STATUS_ORDER = ("changed", "renamed", "new", "removed", "unchanged")
CYCLES_COLUMNS = frozenset(c.key for c in COLUMNS if c.path[0] == "cycles")
STACK_KEYS = {"total": "stack", "step": "stack_step"}


@dataclass(frozen=True)
class Baseline:
    """A baseline's rows, and by row name what else each image records: where it came from
    (ELF, commit, toolchain) and its section and symbol sizes (``--symbols`` compares them)."""
    file: str
    rows: list[Row]
    facts: dict[str, ImageFacts] = field(default_factory=dict)
    keys: dict[str, str] = field(default_factory=dict)      # row name -> its key in the file, images[i]


def _text(path: str, key: str, value: object) -> str | None:
    if value is not None and not isinstance(value, str):
        raise InputError(path, key, "must be a string")
    return value


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
    stack = image.get("stack")
    unknown = {}
    if isinstance(stack, dict) and "unknown" in stack:
        if not isinstance(stack["unknown"], dict):
            raise InputError(path, key + ".stack.unknown", "must be an object")
        for figure, why in stack["unknown"].items():
            if figure not in STACK_KEYS or not isinstance(why, str):
                raise InputError(path, "%s.stack.unknown.%s" % (key, figure), "must be a reason (a string) of step or total")
            unknown[STACK_KEYS[figure]] = why
    cycles = image.get("cycles")
    script = _text(path, key + ".cycles.script_sha256", cycles.get("script_sha256")) if isinstance(cycles, dict) else None
    budget = image.get("budget", {})
    if not isinstance(budget, dict) or not all(
            k in COLUMN and isinstance(v, int) and not isinstance(v, bool) for k, v in budget.items()):
        raise InputError(path, key + ".budget", "must map columns to whole numbers")
    return Row(names[0], names[1], values, unknown, _text(path, key + ".tables_sha256", image.get("tables_sha256")),
               script, dict(budget))


def read_baseline(path: str) -> Baseline:
    """The rows of a JSON report written by ``swarmvm footprint --json`` of this format version;
    InputError naming the file and the key for anything else."""
    data = read_json_document(path, REPORT_FORMAT, REPORT_VERSION, "footprint report",
                              "write it again with swarmvm footprint --json")
    images = data.get("images")
    if not isinstance(images, list):
        raise InputError(path, "images", "must be a list")
    rows, facts, keys = [], {}, {}
    for index, image in enumerate(images):
        key = "images[%d]" % index
        row = _image_row(path, key, image)
        if row.name in keys:
            raise InputError(path, key, "a second row %s" % row.name)
        keys[row.name] = key
        facts[row.name] = baseline_facts(path, key, cast(dict[str, Any], image))      # an object: _image_row checked it
        rows.append(row)
    return Baseline(path, rows, facts, keys)


NOT_MEASURED = "not measured"


def _state(row: Row, column: str) -> str:
    """A figure's state when it has no value: "unknown" or "not measured"."""
    return "unknown" if column in row.unknown else NOT_MEASURED


@dataclass(frozen=True)
class Change:
    """One column of a row against the baseline: two values, or a value on one side only (the
    other unknown or not measured: ``before``/``after`` say which); ``problem`` says why the
    delta gate cannot judge it (it then fails that gate)."""
    column: str
    old: int | None
    new: int | None
    before: str = ""                # the old state without a value
    after: str = ""
    problem: str = ""

    @property
    def delta(self) -> int:
        return 0 if self.old is None or self.new is None else self.new - self.old

    @property
    def changed(self) -> bool:
        return self.old != self.new or self.before != self.after or bool(self.problem)

    def grew_over(self, percent: Fraction) -> bool:
        return self.old is not None and self.new is not None and self.delta * 100 > percent * self.old

    def _figure(self, value: int | None, state: str) -> str:
        return "%d %s" % (value, COLUMN[self.column].unit) if value is not None else state

    def text(self) -> str:
        """``+512 B, +5.69 %``; from 0, ``+12 B, from 0``; ``was 145 B``, ``was unknown``."""
        unit = COLUMN[self.column].unit
        if self.old is None or self.new is None:
            return "was %s" % self._figure(self.old, self.before)
        if self.old == 0:
            return "%+d %s, from 0" % (self.delta, unit)
        return "%+d %s, %+.2f %%" % (self.delta, unit, 100 * self.delta / self.old)

    def transition(self) -> str:
        """``stack (was 145 B, now unknown: ...)``: what the gate cannot judge, for its failure line."""
        return "%s (was %s, now %s%s)" % (self.column, self._figure(self.old, self.before),
                                          self._figure(self.new, self.after), ": " + self.problem if self.problem else "")


@dataclass(frozen=True)
class RowDelta:
    """A row against the baseline: ``row`` is the report's (the baseline's when removed);
    ``old_name`` the baseline's row a renamed one was matched with; ``budgets`` each budget that
    differs from the baseline's, (old, new), None where there was none."""
    row: Row
    status: str
    changes: dict[str, Change]
    old_name: str = ""
    budgets: dict[str, tuple[int | None, int | None]] = field(default_factory=dict)


def _change(column: str, before: Row, after: Row) -> Change | None:
    """The change of one column, or None when neither row has it."""
    old, new = before.values.get(column), after.values.get(column)
    was = "" if old is not None else _state(before, column)
    now = "" if new is not None else _state(after, column)
    if old is None and new is None and was == now:
        return None if was == NOT_MEASURED else Change(column, None, None, was, now)
    problem = ""
    if (old is None) != (new is None):
        problem = "became %s" % now if new is None else "%s in the baseline" % was
        if new is None and column in after.unknown:
            problem = after.unknown[column]
        elif new is None:
            problem = "no longer measured"
    elif column in CYCLES_COLUMNS and old is not None:
        if before.script_sha256 is None:
            problem = "the baseline does not record its event script's digest (write it again)"
        elif before.script_sha256 != after.script_sha256:
            problem = "measured with another event script (sha256 %s..., the baseline's %s...)" % (
                (after.script_sha256 or "")[:12], before.script_sha256[:12])
    return Change(column, old, new, was, now, problem)


def _compared(before: Row, after: Row, status: str, budget: dict[str, int], old_name: str = "") -> RowDelta:
    changes = {c.key: change for c in COLUMNS if (change := _change(c.key, before, after)) is not None}
    budgets = {column: (before.budget.get(column), budget.get(column))
               for column in sorted(before.budget.keys() | budget.keys()) if before.budget.get(column) != budget.get(column)}
    if status != "renamed":
        status = "changed" if any(c.changed for c in changes.values()) or budgets else "unchanged"
    return RowDelta(after, status, changes, old_name, budgets)


def compare(rows: list[Row], baseline: Baseline, budgets: dict[str, dict[str, int]] | None = None) -> list[RowDelta]:
    """Every row of the report and the baseline: changed, renamed, new, removed, then unchanged
    rows; ``budgets``: each row's budget now (by row name), to show one that changed. InputError
    when the baseline holds images of other targets only."""
    budgets = budgets or {}
    old = {row.name: row for row in baseline.rows}
    new = {row.name: row for row in rows}
    old_targets, new_targets = {r.target for r in baseline.rows}, {r.target for r in rows}
    if old_targets and new_targets and not old_targets & new_targets:
        raise InputError(baseline.file, "images", "a baseline of %s images, the report's are %s: the targets differ, "
                         "nothing can be compared (use a baseline of the same target)"
                         % (", ".join(sorted(old_targets)), ", ".join(sorted(new_targets))))
    renamed: dict[str, str] = {}                      # new name -> old name: same target and table image
    for name in sorted(new.keys() - old.keys()):
        digest = new[name].tables_sha256
        same = [o for o in sorted(old.keys() - new.keys()) if digest is not None and old[o].target == new[name].target
                and old[o].tables_sha256 == digest and o not in renamed.values()]
        if len(same) == 1:
            renamed[name] = same[0]
    deltas = []
    for name in sorted(old.keys() | new.keys()):
        if name in renamed:
            deltas.append(_compared(old[renamed[name]], new[name], "renamed", budgets.get(name, {}), renamed[name]))
        elif name in renamed.values():
            continue
        elif name not in old:
            deltas.append(RowDelta(new[name], "new", {}))
        elif name not in new:
            deltas.append(RowDelta(old[name], "removed", {}))
        else:
            deltas.append(_compared(old[name], new[name], "", budgets.get(name, {})))
    return sorted(deltas, key=lambda d: (STATUS_ORDER.index(d.status), d.row.target, d.row.supervisor))


def _total(deltas: list[RowDelta], column: str) -> str:
    both = [d.changes[column] for d in deltas if column in d.changes
            and d.changes[column].old is not None and d.changes[column].new is not None]
    return "%s (%s)" % (COLUMN[column].label, Change(column, sum(c.old or 0 for c in both),
                                                       sum(c.new or 0 for c in both)).text())


def _compared_count(deltas: list[RowDelta]) -> int:
    return sum(d.status in ("changed", "renamed", "unchanged") for d in deltas)


def summary(deltas: list[RowDelta], baseline: Baseline) -> str:
    """One line: how many rows changed, came and went, and the flash and RAM totals' change over
    the rows in both."""
    count = {status: sum(d.status == status for d in deltas) for status in STATUS_ORDER}
    both = _compared_count(deltas)
    shown = [s for s in STATUS_ORDER if s != "renamed" or count[s]]
    return "Against %s: %s; in total over the %d row%s in both: %s, %s." % (
        baseline.file, ", ".join("%d %s" % (count[s], s) for s in shown), both, "" if both == 1 else "s",
        _total(deltas, "flash"), _total(deltas, "ram"))


def growth(deltas: list[RowDelta], percent: float, baseline: Baseline | None = None) -> dict[str, str]:
    """Row name -> why the delta gate fails it: what grew by more than ``percent`` per cent, and
    what it cannot judge (a figure that became unknown or unmeasured, or the reverse; cycles of
    another event script; a new row while a row of its target was removed); the baseline's file
    -> "nothing compared" when no row is in both. The float is taken as the decimal it was written
    as (0.3, not 0.29999...), so the boundary is the one the user typed."""
    exact = Fraction(repr(percent))
    found = {}
    removed: dict[str, list[str]] = {}
    for delta in deltas:
        if delta.status == "removed":
            removed.setdefault(delta.row.target, []).append(delta.row.name)
    for delta in deltas:
        texts = []
        over = [c for c in delta.changes.values() if c.grew_over(exact) and not c.problem]
        if over:
            texts.append("grew by more than %g %%: %s" % (
                percent, ", ".join("%s (%s)" % (c.column, c.text()) for c in over)))
        judged = [c for c in delta.changes.values() if c.problem]
        if judged:
            texts.append("cannot be judged: %s" % ", ".join(c.transition() for c in judged))
        if delta.status == "new" and delta.row.target in removed:
            texts.append("new, while %s is removed: an image renamed? its growth cannot be judged (name the ELF as "
                         "in the baseline, or write the baseline again)" % ", ".join(removed[delta.row.target]))
        if texts:
            found[delta.row.name] = "; ".join(texts)
    if baseline is not None and deltas and not _compared_count(deltas):
        found[baseline.file] = "nothing compared: no row of the report is in the baseline (write the baseline again)"
    return found
