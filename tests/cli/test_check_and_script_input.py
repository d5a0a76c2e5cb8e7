"""`check --properties --all` lists every finding (the report cut them at "... and N more" with
no way to see the rest), `--all` alone is a usage error, `trace --script -` reads the script
from standard input (it was taken as a file named "-"), and a missing input file is the one
documented error line on every verb that reads one (issue 27)."""

from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

EXAMPLES = Path(__file__).parents[2] / "examples"
WORKER = str(EXAMPLES / "energy_worker" / "supervisor.yaml")
FORAGER = str(EXAMPLES / "learning" / "supervisor.yaml")      # 4 pairs of events that are not confluent


def confluence_lines(report: str) -> list[str]:
    lines = report.splitlines()
    start = lines.index("- not confluent: 4") + 1
    return [line for line in lines[start:] if line.startswith("  - ")]


def test_check_properties_cuts_its_findings_and_says_how_to_see_them():
    result = CliRunner().invoke(main, ["check", "--properties", FORAGER])
    assert result.exit_code == 0
    assert confluence_lines(result.stdout)[3:] == ["  - ... and 1 more (check --properties --all lists them)"]


def test_check_properties_all_lists_every_finding():
    result = CliRunner().invoke(main, ["check", "--properties", "--all", FORAGER])
    assert result.exit_code == 0
    findings = confluence_lines(result.stdout)
    assert len(findings) == 4 and not any("more" in line for line in findings)
    assert findings[3] == "  - EV_run or EV_walk: EV_run disables EV_walk after EV_far"


def test_all_without_properties_is_a_usage_error():
    result = CliRunner().invoke(main, ["check", "--all", FORAGER])
    assert (result.exit_code, result.stdout, result.stderr) == (2, "", "swarmvm: error: --all: only with --properties\n")


def test_trace_reads_the_script_from_standard_input(tmp_path):
    script = CliRunner().invoke(main, ["script", WORKER, "--steps", "20", "--seed", "3"]).stdout
    (tmp_path / "events.txt").write_text(script)
    from_file = CliRunner().invoke(main, ["trace", WORKER, "--script", str(tmp_path / "events.txt")])
    from_stdin = CliRunner().invoke(main, ["trace", WORKER, "--script", "-"], input=script)
    assert from_stdin.exit_code == 0 and from_stdin.stderr == ""
    assert from_stdin.stdout == from_file.stdout and len(from_stdin.stdout.splitlines()) == 20


def test_a_bad_script_on_standard_input_is_one_error_line():
    result = CliRunner().invoke(main, ["trace", WORKER, "--script", "-"], input="EV_bogus\n")
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == "swarmvm: error: <stdin>: line 1: event EV_bogus: unknown event\n"


MISSING = "nope.yaml"
READERS = [["check", MISSING], ["check", "--properties", MISSING], ["pack", MISSING, "-o", "x.svm"],
           ["gen", MISSING, "-t", "c", "-o", "out"], ["script", MISSING], ["trace", WORKER, "--script", "nope.txt"],
           ["equiv", WORKER, MISSING], ["export", MISSING, "-f", "yaml", "-o", "x.yaml"]]


@pytest.mark.parametrize("args", READERS, ids=[" ".join(a) for a in READERS])
def test_a_missing_input_file_is_the_documented_error_line(args, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, args)
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr.startswith("swarmvm: error: nope.") and "cannot read file" in result.stderr
    assert result.stderr.count("\n") == 1 and not list(tmp_path.iterdir())
