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
for each.

A check fails closed: a figure that was measured but is not known (a stack bound behind an
undeclared indirect call) fails it, saying why, unless the budget lets that column be unknown
(``allow_unknown = ["stack"]`` in a target's or row's table), which the report shows as not
checked. A figure the run was not asked for (cycles without ``--cycles``) is not checked either,
and shown so (a skipped test case), since measuring it is the command's choice, not the image's."""

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..boundary.errors import InputError, decode_text, read_input
from ..boundary.structure import check_structure
from ..targets import TARGETS as ALL_TARGETS
from .measure import COLUMN, Limits, Row, robot_limits

PYPROJECT = "pyproject.toml"
PYPROJECT_TABLE = ("tool", "swarmvm", "footprint")
TARGETS = tuple(sorted(name for name, target in ALL_TARGETS.items() if target.elf is not None))   # measured ones


ALLOW_UNKNOWN = "allow_unknown"        # the opt-out key: columns whose unknown figure is not checked


@dataclass(frozen=True)
class Budgets:
    """Bounds by column key: per target, and per (target, supervisor) replacing the target's;
    the columns each may leave unknown (``allow_unknown``, a row's replacing its target's); the
    dotted key of each row's table (an error names it when it matches no image)."""
    file: str = ""
    targets: dict[str, dict[str, int]] = field(default_factory=dict)
    rows: dict[tuple[str, str], dict[str, int]] = field(default_factory=dict)
    allowed: dict[tuple[str, str | None], frozenset[str]] = field(default_factory=dict)
    row_keys: dict[tuple[str, str], str] = field(default_factory=dict)

    def of(self, target: str, supervisor: str) -> dict[str, int]:
        return {**self.targets.get(target, {}), **self.rows.get((target, supervisor), {})}

    def allows(self, target: str, supervisor: str) -> tuple[frozenset[str], str]:
        """The columns the row may leave unknown, and the dotted key that says so."""
        for key in ((target, supervisor), (target, None)):
            if key in self.allowed:
                table = self.row_keys.get((target, supervisor), target) if key[1] is not None else target
                return self.allowed[key], "%s.%s" % (table, ALLOW_UNKNOWN)
        return frozenset(), ""

    def check_rows(self, names: set[tuple[str, str]]) -> None:
        """InputError for a row's table naming no image measured of a target that has some: a
        renamed ELF would otherwise escape its row's bounds without a word."""
        targets = {target for target, _ in names}
        for (target, supervisor), key in sorted(self.row_keys.items()):
            if target in targets and (target, supervisor) not in names:
                measured = ", ".join(s for t, s in sorted(names) if t == target)
                raise InputError(self.file, key, "no %s image named %s among those measured (%s): rename the "
                                 "table or the ELF" % (target, supervisor, measured))


def _table(file: str, key: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise InputError(file, key, "must be a table, got %s" % type(value).__name__)
    return value


def _allowed(file: str, key: str, value: Any) -> frozenset[str]:
    """The columns of an ``allow_unknown`` list; InputError for anything else."""
    if not isinstance(value, list) or not all(isinstance(c, str) for c in value):
        raise InputError(file, key, "must be a list of column names, got %r" % (value,))
    for column in value:
        if column not in COLUMN:
            raise InputError(file, key, "unknown column %r (one of %s)" % (column, ", ".join(sorted(COLUMN))))
    return frozenset(value)


def _bounds(file: str, key: str, table: dict[str, Any]) -> dict[str, int]:
    """The column bounds of one table (a target's without its ``rows``, or a row's)."""
    bounds = {}
    for column, value in table.items():
        if column == ALLOW_UNKNOWN:
            continue
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
    allowed: dict[tuple[str, str | None], frozenset[str]] = {}
    row_keys = {}
    for target, table in data.items():
        key = ".".join(prefix + (target,))
        if target not in TARGETS:
            raise InputError(file, key, "unknown target (one of %s)" % ", ".join(TARGETS))
        table = dict(_table(file, key, table))
        for supervisor, row in _table(file, key + ".rows", table.pop("rows", {})).items():
            row_key = "%s.rows.%s" % (key, supervisor)
            row = _table(file, row_key, row)
            rows[(target, supervisor)] = _bounds(file, row_key, row)
            row_keys[(target, supervisor)] = row_key
            if ALLOW_UNKNOWN in row:
                allowed[(target, supervisor)] = _allowed(file, row_key + "." + ALLOW_UNKNOWN, row[ALLOW_UNKNOWN])
        targets[target] = _bounds(file, key, table)
        if ALLOW_UNKNOWN in table:
            allowed[(target, None)] = _allowed(file, key + "." + ALLOW_UNKNOWN, table[ALLOW_UNKNOWN])
    return Budgets(file, targets, rows, allowed, row_keys)


def read_budgets(path: str) -> Budgets:
    """The budgets of a TOML file (``[tool.swarmvm.footprint]`` in a ``pyproject.toml``)."""
    text = decode_text(path, read_input(path))
    check_structure(path, text, comment="#")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(path, "", "not a TOML file (%s)" % exc)
    return parse_budgets(path, data, PYPROJECT_TABLE if Path(path).name == PYPROJECT else ())


HOW_TO_KNOW = {"stack": "declare what it calls (--indirect, --frame FUNCTION=BYTES, a library's .su files); or let it "
                        "be unknown: allow_unknown = [\"stack\"] in the budget",
               "cycles": "give --cycles SCRIPT"}


@dataclass(frozen=True)
class Check:
    """``value <= bound`` for one row and column; ``kind`` is "limit" or "budget". Fails closed:
    a figure measured but not known fails, unless ``allowed`` (the budget key that lets it be
    unknown); a figure not measured at all (cycles without --cycles) is skipped, and says so."""
    row: Row
    kind: str
    column: str
    bound: int
    failure: str        # what the report says when the row's value is over the bound
    allowed: str = ""   # the allow_unknown key that lets this column be unknown, if any

    @property
    def value(self) -> int | None:
        return self.row.values.get(self.column)

    @property
    def status(self) -> str:
        """"passed", "failed" (over the bound, or unknown) or "skipped" (not measured, or allowed unknown)."""
        if self.value is not None:
            return "passed" if self.value <= self.bound else "failed"
        return "skipped" if self.allowed or self.column not in self.row.unknown else "failed"

    @property
    def passed(self) -> bool:
        return self.status != "failed"

    @property
    def message(self) -> str:
        """What the report says of a check that did not pass, or was skipped."""
        if self.value is not None:
            return self.failure
        unit = COLUMN[self.column].unit
        what = "its %s of %d %s" % (self.kind, self.bound, unit)
        if self.column not in self.row.unknown:
            return "%s not measured, %s not checked (%s)" % (self.column, what, HOW_TO_KNOW["cycles"])
        reason = "%s unknown (%s)" % (self.column, self.row.unknown[self.column])
        if self.allowed:
            return "%s, %s not checked (allowed by %s)" % (reason, what, self.allowed)
        return "%s: %s cannot be checked (%s)" % (reason, what, HOW_TO_KNOW["stack"])

    @property
    def title(self) -> str:
        unit = COLUMN[self.column].unit
        return "%s <= %d %s (%s)" % (self.column, self.bound, unit, self.kind)


def _limit_checks(row: Row, limits: Limits, allowed: tuple[frozenset[str], str]) -> list[Check]:
    """The row's robot's hard limits (its target's record) and the seed's KPI. The SRAM check of
    static RAM plus the worst-case stack is made whether the stack is known or not: unknown, it
    fails (or is skipped where the budget allows the stack unknown)."""
    found = []
    robot = limits.robots.get(row.target)
    if robot is not None:
        flash, ram = row.values["flash"], row.values["ram"]
        found.append(Check(row, "limit", "flash", robot.flash,
                           "flash %d B exceeds the %s's %d B" % (flash, robot.robot, robot.flash)))
        found.append(Check(row, "limit", "ram", robot.sram - robot.min_stack,
                           "static RAM %d B leaves %d B of the %d B SRAM for the stack, below %d B"
                           % (ram, robot.sram - ram, robot.sram, robot.min_stack)))
        if "stack" in row.values or "stack" in row.unknown:
            stack = row.values.get("stack", 0)
            found.append(Check(row, "limit", "stack", robot.sram - ram,
                               "static RAM %d B + worst-case stack %d B = %d B exceeds the %s's %d B SRAM"
                               % (ram, stack, ram + stack, robot.robot, robot.sram),
                               allowed[1] if "stack" in allowed[0] else ""))
    found.append(Check(row, "limit", "vm", limits.vm,
                       "the VM takes %d B, above the %d B KPI" % (row.values["vm"], limits.vm)))
    return found


def checks(rows: list[Row], limits: Limits, budgets: Budgets) -> list[Check]:
    """Every check of every row: its limits, then its budgets, each whether the row's figure is
    known or not (Check.status)."""
    found = []
    for row in rows:
        allowed = budgets.allows(row.target, row.supervisor)
        found += _limit_checks(row, limits, allowed)
        for column, bound in sorted(budgets.of(row.target, row.supervisor).items()):
            value, unit = row.values.get(column, 0), COLUMN[column].unit
            found.append(Check(row, "budget", column, bound, "%s %d %s over its budget of %d %s (by %d %s)"
                               % (column, value, unit, bound, unit, value - bound, unit),
                               allowed[1] if column in allowed[0] else ""))
    return found


# The robot's memory each column's figure is a share of (RobotLimits' field): a part of flash or of
# static RAM, and a stack, which lives in the SRAM. The VM figure is flash and RAM together, and
# cycles are time: neither is a share of one memory.
CAPACITY = {"flash": "flash", "flash_core": "flash", "flash_tables": "flash", "flash_application": "flash",
            "ram": "sram", "ram_core": "sram", "ram_tables": "sram", "ram_application": "sram",
            "stack": "sram", "stack_step": "sram"}
NO_CAPACITY = {"vm": "VM is flash and RAM together, a share of neither",
               "cycles": "the target's record gives no cycles a step may take",
               "cycles_mean": "the target's record gives no cycles a step may take"}


def capacity(target: str, column: str) -> tuple[int | None, str]:
    """The robot's own capacity a figure of ``column`` takes a share of, from its target's record
    (the real robot's, not the limits a run replaced), and what it is (``Kilobot flash``); or
    None and why there is none: never an invented one."""
    memory = CAPACITY.get(column)
    if memory is None:
        return None, NO_CAPACITY.get(column, "no capacity is known for %s" % column)      # escaped: the package's names; markdown() where written
    robot = robot_limits().get(target)
    if robot is None:
        return None, "the %s target's record gives no flash or SRAM size" % target      # escaped: the package's names; markdown() where written
    return getattr(robot, memory), "%s %s" % (robot.robot, "SRAM" if memory == "sram" else memory)      # escaped: the package's names; markdown() where written
