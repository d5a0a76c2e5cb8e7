"""Footprint budgets and the checks of a report: the robots' hard limits (built in) and the
budgets a team writes once in TOML, per target and optionally per row (docs/footprint.md,
"Budgets").

A budget file holds one table per target, each column a bound in bytes, and under ``rows`` a
table per supervisor (the ELF's name) whose columns replace the target's::

    [kilobot]
    flash = 16000
    [kilobot.rows.energy_worker]
    flash = 9000

A file named ``pyproject.toml`` holds the same tables under ``[tool.swarmvm.footprint]``.
Every figure is checked the same way, ``value <= bound``, so a limit and a budget are one
:class:`Check` each: the report prints the exceeded ones, the JUnit report has a test case
for each."""

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..boundary.errors import InputError, decode_text, read_input
from ..boundary.structure import check_structure
from ..targets import TARGETS as ALL_TARGETS
from .measure import COLUMN, Limits, Row

PYPROJECT = "pyproject.toml"
PYPROJECT_TABLE = ("tool", "swarmvm", "footprint")
TARGETS = tuple(sorted(name for name, target in ALL_TARGETS.items() if target.elf is not None))   # measured ones


@dataclass(frozen=True)
class Budgets:
    """Bounds by column key: per target, and per (target, supervisor) replacing the target's."""
    file: str = ""
    targets: dict[str, dict[str, int]] = field(default_factory=dict)
    rows: dict[tuple[str, str], dict[str, int]] = field(default_factory=dict)

    def of(self, target: str, supervisor: str) -> dict[str, int]:
        return {**self.targets.get(target, {}), **self.rows.get((target, supervisor), {})}


def _table(file: str, key: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise InputError(file, key, "must be a table, got %s" % type(value).__name__)
    return value


def _bounds(file: str, key: str, table: dict[str, Any]) -> dict[str, int]:
    """The column bounds of one table (a target's without its ``rows``, or a row's)."""
    bounds = {}
    for column, value in table.items():
        where = "%s.%s" % (key, column)
        if column not in COLUMN:
            raise InputError(file, where, "unknown column (one of %s)" % ", ".join(sorted(COLUMN)))
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise InputError(file, where, "must be a whole number (%s), at least 0, got %r" % (COLUMN[column].unit, value))
        bounds[column] = value
    return bounds


def parse_budgets(file: str, data: dict[str, Any], prefix: tuple[str, ...] = ()) -> Budgets:
    """Budgets from parsed TOML, its tables under ``prefix``; InputError naming the file and
    the dotted key of the first thing wrong."""
    for depth, key in enumerate(prefix):
        data = _table(file, ".".join(prefix[:depth + 1]), data.get(key, {}))
    targets, rows = {}, {}
    for target, table in data.items():
        key = ".".join(prefix + (target,))
        if target not in TARGETS:
            raise InputError(file, key, "unknown target (one of %s)" % ", ".join(TARGETS))
        table = dict(_table(file, key, table))
        for supervisor, row in _table(file, key + ".rows", table.pop("rows", {})).items():
            row_key = "%s.rows.%s" % (key, supervisor)
            rows[(target, supervisor)] = _bounds(file, row_key, _table(file, row_key, row))
        targets[target] = _bounds(file, key, table)
    return Budgets(file, targets, rows)


def read_budgets(path: str) -> Budgets:
    """The budgets of a TOML file (``[tool.swarmvm.footprint]`` in a ``pyproject.toml``)."""
    text = decode_text(path, read_input(path))
    check_structure(path, text, comment="#")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(path, "", "not a TOML file (%s)" % exc)
    return parse_budgets(path, data, PYPROJECT_TABLE if Path(path).name == PYPROJECT else ())


@dataclass(frozen=True)
class Check:
    """``value <= bound`` for one row and column; ``kind`` is "limit" or "budget"."""
    row: Row
    kind: str
    column: str
    bound: int
    failure: str        # what the report says when the row's value is over the bound

    @property
    def value(self) -> int:
        return self.row.values[self.column]

    @property
    def passed(self) -> bool:
        return self.value <= self.bound

    @property
    def title(self) -> str:
        unit = COLUMN[self.column].unit
        return "%s <= %d %s (%s)" % (self.column, self.bound, unit, self.kind)


def _limit_checks(row: Row, limits: Limits) -> list[Check]:
    """The row's robot's hard limits (its target's record) and the seed's KPI."""
    found = []
    robot = limits.robots.get(row.target)
    if robot is not None:
        flash, ram = row.values["flash"], row.values["ram"]
        found.append(Check(row, "limit", "flash", robot.flash,
                           "flash %d B exceeds the %s's %d B" % (flash, robot.robot, robot.flash)))
        found.append(Check(row, "limit", "ram", robot.sram - robot.min_stack,
                           "static RAM %d B leaves %d B of the %d B SRAM for the stack, below %d B"
                           % (ram, robot.sram - ram, robot.sram, robot.min_stack)))
        if "stack" in row.values:                   # a known worst case: it and static RAM must fit the SRAM
            stack = row.values["stack"]
            found.append(Check(row, "limit", "stack", robot.sram - ram,
                               "static RAM %d B + worst-case stack %d B = %d B exceeds the %s's %d B SRAM"
                               % (ram, stack, ram + stack, robot.robot, robot.sram)))
    found.append(Check(row, "limit", "vm", limits.vm,
                       "the VM takes %d B, above the %d B KPI" % (row.values["vm"], limits.vm)))
    return found


def checks(rows: list[Row], limits: Limits, budgets: Budgets) -> list[Check]:
    """Every check of every row: its limits, then its budgets (columns it has a figure for)."""
    found = []
    for row in rows:
        found += _limit_checks(row, limits)
        for column, bound in sorted(budgets.of(row.target, row.supervisor).items()):
            if column in row.values:
                value, unit = row.values[column], COLUMN[column].unit
                found.append(Check(row, "budget", column, bound, "%s %d %s over its budget of %d %s (by %d %s)"
                                   % (column, value, unit, bound, unit, value - bound, unit)))
    return found
