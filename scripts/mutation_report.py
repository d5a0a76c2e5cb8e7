"""The mutation report (docs/mutation.md): per module, killed / survived / equivalent / timeout
mutants and the kill rate with equivalent mutants set aside; exit status 1 when a module is under
the threshold.

Its input is what scripts/mutation.py leaves in the work folder: one ``<slug>.mutants.json`` per
module, a list of mutants each with the module, the operator, the line and column mutated, the
mutated line's original text, its mutated text and the outcome the tests gave. Equivalent mutants
(ones no test can tell from the original: the mutation does not change what the code does) are
listed in tests/mutation/equivalents.toml with the reason, so they are examined once; a mutant is
identified there by module, operator, the original line's text and the column, which stay the same
while other lines of the module move."""

import argparse
import json
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

THRESHOLD = 97.0        # per cent killed, equivalents excluded, that every module must reach
OUTCOMES = ("killed", "timeout", "survived", "incompetent")


@dataclass(frozen=True)
class Mutant:
    """One mutant as the run recorded it; ``outcome`` is one of OUTCOMES."""

    module: str
    operator: str
    line: int
    column: int
    text: str           # the line's original text, stripped
    mutated: str        # the line as the mutant has it, stripped
    outcome: str

    @property
    def key(self) -> tuple[str, str, str, int]:
        return (self.module, self.operator, self.text, self.column)


@dataclass
class ModuleResult:
    """The counts of one module, and the mutants that survived (not marked equivalent)."""

    module: str
    counts: dict[str, int] = field(default_factory=lambda: dict.fromkeys(OUTCOMES + ("equivalent",), 0))
    survivors: list[Mutant] = field(default_factory=list)

    @property
    def considered(self) -> int:
        """Mutants the rate is over: all but the equivalent ones."""
        return sum(self.counts[outcome] for outcome in OUTCOMES)

    @property
    def rate(self) -> float:
        """Per cent killed (a timeout is a kill: the mutant made the tests hang), equivalents set
        aside; 100 when nothing is left to kill."""
        if not self.considered:
            return 100.0
        return 100.0 * (self.counts["killed"] + self.counts["timeout"]) / self.considered


def load_equivalents(path: Path) -> dict[tuple[str, str, str, int], str]:
    """{mutant key: reason} from the equivalents file; ValueError for an entry without a reason."""
    table = tomllib.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    equivalents = {}
    for entry in table.get("equivalent", []):
        if not entry.get("reason", "").strip():
            raise ValueError("%s: equivalent mutant %s:%r without a reason" % (path, entry.get("module"), entry.get("line")))
        equivalents[(entry["module"], entry["operator"], entry["line"].strip(), int(entry["column"]))] = entry["reason"]
    return equivalents


def load_mutants(path: Path) -> list[Mutant]:
    return [Mutant(**record) for record in json.loads(path.read_text(encoding="utf-8"))]


def tally(mutants: list[Mutant], equivalents: dict[tuple[str, str, str, int], str]) -> list[ModuleResult]:
    """Each module's result, modules in the order they first appear."""
    results: dict[str, ModuleResult] = {}
    for mutant in mutants:
        result = results.setdefault(mutant.module, ModuleResult(mutant.module))
        if mutant.outcome == "survived" and mutant.key in equivalents:
            result.counts["equivalent"] += 1
            continue
        result.counts[mutant.outcome] += 1
        if mutant.outcome in ("survived", "incompetent"):
            result.survivors.append(mutant)
    return list(results.values())


def markdown(results: list[ModuleResult], threshold: float) -> str:
    """The report as Markdown: the table of modules, then each survivor's line and mutation."""
    lines = ["# Mutation report", "",
             "Kill rate: killed and timed-out mutants over all mutants but the equivalent ones "
             "(tests/mutation/equivalents.toml); every module must reach %.0f %%." % threshold, "",
             "| module | mutants | killed | timeout | survived | incompetent | equivalent | kill rate |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in results:
        c = r.counts
        mark = "" if r.rate >= threshold else " (under)"
        lines.append("| %s | %d | %d | %d | %d | %d | %d | %.1f %%%s |" % (
            r.module, r.considered + c["equivalent"], c["killed"], c["timeout"], c["survived"], c["incompetent"],
            c["equivalent"], r.rate, mark))
    for r in results:
        if r.survivors:
            lines += ["", "## Survivors in %s" % r.module, ""]
            lines += ["- line %d, column %d, %s: `%s` -> `%s`%s" % (
                m.line, m.column, m.operator, m.text, m.mutated, "" if m.outcome == "survived" else " (" + m.outcome + ")")
                for m in r.survivors]
    return "\n".join(lines) + "\n"


def as_json(results: list[ModuleResult], threshold: float) -> dict:
    return {"threshold": threshold,
            "modules": [{"module": r.module, **r.counts, "rate": round(r.rate, 2),
                         "survivors": [{"line": m.line, "column": m.column, "operator": m.operator, "text": m.text,
                                        "mutated": m.mutated, "outcome": m.outcome} for m in r.survivors]}
                        for r in results]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("work", type=Path, help="the run's work folder (its *.mutants.json)")
    parser.add_argument("--equivalents", type=Path, default=Path("tests/mutation/equivalents.toml"))
    parser.add_argument("--threshold", type=float, default=THRESHOLD)
    parser.add_argument("--also", type=Path, action="append", default=[], metavar="WORK",
                        help="another run's work folder whose modules are reported too (the C runtime's, "
                             "build/mutation-c, from scripts/mutation_c.py)")
    args = parser.parse_args(argv)
    mutants = [m for folder in (args.work, *args.also) for path in sorted(folder.glob("*.mutants.json"))
               for m in load_mutants(path)]
    results = tally(mutants, load_equivalents(args.equivalents))
    (args.work / "report.md").write_text(markdown(results, args.threshold), encoding="utf-8")
    (args.work / "report.json").write_text(json.dumps(as_json(results, args.threshold), indent=1) + "\n",
                                           encoding="utf-8")
    print("mutation report: %s" % (args.work / "report.md"))
    under = [r for r in results if r.rate < args.threshold]
    for r in results:
        print("  %-36s %5.1f %% of %d%s" % (r.module, r.rate, r.considered, "  UNDER" if r in under else ""))
    return 1 if under or not results else 0


if __name__ == "__main__":
    sys.exit(main())
