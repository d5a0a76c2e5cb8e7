"""Issue 13's scorecard: every speed and size target of the issue beside the figure `make bench`
and `make footprint` measured for it, read from their JSON files in build/ (so it times
nothing itself), with a one-line summary; ``--json FILE`` writes the same rows.

A figure whose file is missing (its benchmark was not run) is shown as such, never guessed.
The streaming targets (10 M steps under 100 MB) are tests, not benchmarks: they are listed with
the test that holds them."""

import argparse
import json
from pathlib import Path

from figures import add_json_option, write_figures

BUILD = Path(__file__).resolve().parent.parent / "build"
KILOBOT_CORE = 4096         # bytes: "at most 4 kB"
CAPBOT_CORE = 3072
VM_RAM = 64


def read(name: str) -> dict | None:
    """The JSON a benchmark wrote under build/, or None when it has not run."""
    path = BUILD / name
    return json.loads(path.read_text()) if path.exists() else None


def least(rows: list, ratio) -> tuple[float, str]:
    """The smallest value of ``ratio(row)`` and the supervisor it belongs to."""
    row = min(rows, key=ratio)
    return ratio(row), row.get("supervisor") or row.get("name", "?")


def largest(rows: list, value) -> tuple[float, str]:
    """The largest value of ``value(row)`` and the supervisor it belongs to."""
    row = max(rows, key=value)
    return value(row), row.get("supervisor") or row.get("name", "?")


def targets() -> list[dict]:
    """One row per target: what the issue asks, what was measured (worst case over the
    supervisors, named), and whether it is met (None: not measured)."""
    python, cpp, c_host = read("bench/python_vs_baseline.json"), read("bench/cpp_steps.json"), read("bench/c_host.json")
    avr, m4, footprint = read("bench/avr_cycles.json"), read("bench/m4_cycles.json"), read("footprint.json")
    rows = []

    def add(item: str, target: str, measured, met_if, unit: str = "x") -> None:
        if measured is None:
            rows.append(dict(item=item, target=target, measured="not measured", met=None))
            return
        value, where = measured
        text = ("%.2fx" % value if unit == "x" else "{:,} {}".format(int(value), unit)) + " (%s)" % where
        rows.append(dict(item=item, target=target, measured=text, met=None if met_if is None else bool(met_if(value))))

    add("1. Python VM steps", ">= 2x on every supervisor",
        least(python["rows"], lambda r: r["steps"] / r["steps_baseline"]) if python else None, lambda v: v >= 2.0)
    add("2. C++ VM steps", ">= 2x on every supervisor",
        least(cpp["rows"], lambda r: r["ratio"]) if cpp else None, lambda v: v >= 2.0)
    kilobot = [i for i in footprint["images"] if i["target"] == "kilobot"] if footprint else []
    capbot = [i for i in footprint["images"] if i["target"] == "capbot"] if footprint else []
    add("3. Kilobot core flash, as built (make footprint)", "<= 4,096 B",
        largest(kilobot, lambda i: i["flash"]["core"]) if kilobot else None, lambda v: v <= KILOBOT_CORE, "B")
    add("3. Kilobot core flash at -Os", "<= 4,096 B",
        largest(avr["rows"], lambda r: r["core_flash"]["current_Os"]) if avr else None, lambda v: v <= KILOBOT_CORE, "B")
    add("3. Kilobot VM static RAM", "<= 64 B",
        largest(avr["rows"], lambda r: r["vm_ram"]["current"]) if avr else None, lambda v: v <= VM_RAM, "B")
    add("3. AVR cycles per step", "no slower: >= 1x the baseline's speed",
        least(avr["rows"], lambda r: r["ratio"]) if avr else None, lambda v: v >= 1.0)
    add("3. CapBot core flash (make footprint)", "<= 3,072 B",
        largest(capbot, lambda i: i["flash"]["core"]) if capbot else None, lambda v: v <= CAPBOT_CORE, "B")
    add("3. M4 instructions per step (shown, no target)", "-",
        least(m4["rows"], lambda r: r["ratio"]) if m4 else None, None)
    add("4. Python image load", ">= 5x on every supervisor",
        least(python["rows"], lambda r: r["loads"] / r["loads_baseline"]) if python else None, lambda v: v >= 5.0)
    add("4. C image load (host)", ">= 5x on every supervisor",
        least(c_host["rows"], lambda r: r["load_ratio"]) if c_host else None, lambda v: v >= 5.0)
    add("5. C trace on the host", ">= 1,000,000 steps/s",
        least(c_host["rows"], lambda r: r["trace"]["current"]) if c_host else None, lambda v: v >= 1e6, "steps/s")
    rows.append(dict(item="5. script/trace --steps 10000000", target="< 100 MB", met=None,
                     measured="a test, not a benchmark: tests/cli/test_trace_stream.py, tests/cli/test_script_stream.py"))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_json_option(parser)
    args = parser.parse_args()
    rows = targets()
    print("Issue 13 scorecard (worst supervisor in brackets)")
    print("| target | asked | measured | met |")
    print("|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %s | %s |" % (r["item"], r["target"], r["measured"],
                                         {True: "yes", False: "NO", None: "-"}[r["met"]]))
    judged = [r for r in rows if r["met"] is not None]
    missed = [r["item"] for r in judged if not r["met"]]
    unmeasured = [r["item"] for r in rows if r["measured"] == "not measured"]
    print("issue 13: %d of %d measured targets met%s%s" % (
        len(judged) - len(missed), len(judged), "; NOT met: " + ", ".join(missed) if missed else "",
        "; not measured: " + ", ".join(unmeasured) if unmeasured else ""))
    write_figures(args.json, rows)


if __name__ == "__main__":
    main()
