"""Usage errors of every verb end in one line ``swarmvm: error: NAME: MESSAGE``, exit status 2,
like bad input does (README): click's own form was three lines (Usage:, Try..., Error:)."""

from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

EXAMPLE = str(Path(__file__).parents[2] / "examples" / "energy_worker" / "supervisor.yaml")

# (arguments, the one line after "swarmvm: error: "): each kind of usage error on a few verbs,
# the compiler's and the studies'.
CASES = [
    # a missing argument
    (["check"], "FILES: missing argument"),
    (["equiv", EXAMPLE], "B: missing argument"),
    (["footprint"], "ELFS: missing argument"),
    # a missing option, and an option without its value
    (["pack", EXAMPLE], "--output: missing option"),
    (["trace", EXAMPLE], "--script: missing option"),
    (["sweep", "uav"], "--out: missing option"),
    (["gen", EXAMPLE, "-o", "out"], "--target: missing option (one of argos, c, capbot, kilobot, pipuck, python)"),
    (["script", EXAMPLE, "--steps"], "--steps: Option '--steps' requires an argument."),
    (["sim", "uav", "--mode"], "--mode: Option '--mode' requires an argument."),
    (["check", "--properties=yes", EXAMPLE], "--properties: Option '--properties' does not take a value."),
    # an unknown option
    (["--bogus"], "--bogus: no such option"),
    (["check", EXAMPLE, "--bogus"], "--bogus: no such option"),
    (["script", EXAMPLE, "--step", "3"], "--step: no such option (did you mean --steps, --seed, --help?)"),
    (["bounds", "energy", "--bogus"], "--bogus: no such option"),
    # a bad choice
    (["gen", EXAMPLE, "-t", "z80", "-o", "out"],
     "--target: 'z80' is not one of 'argos', 'c', 'capbot', 'kilobot', 'pipuck', 'python'."),
    (["trace", EXAMPLE, "--script", "s", "--inputs", "both"], "--inputs: 'both' is not one of 'level', 'edge'."),
    (["export", EXAMPLE, "-f", "pdf", "-o", "out"], "--format: 'pdf' is not one of 'yaml', 'gen', 'dot', 'svg'."),
    (["bounds", "energy", "--strategy", "z"], "--strategy: 'z' is not one of 'fixed', 'mobile'."),
    # a value out of range
    (["script", EXAMPLE, "--steps", "0"], "--steps: 0 is not in the range 1<=x<=10000000."),
    (["script", EXAMPLE, "--density", "nan"], "--density: nan is not a finite number."),
    (["script", EXAMPLE, "--seed", "-1"], "--seed: -1 is not in the range 0<=x<=4294967295."),
    (["sim", "uav", "--seed", "-1"], "--seed: -1 is not in the range 0<=x<=4294967295."),   # was a numpy traceback
    (["sweep", "uav", "-o", "out", "--first-seed", "-1"], "--first-seed: -1 is not in the range 0<=x<=4294967295."),
    (["sim", "energy", "--seed", "0"], "--seed: 0 is not in the range 1<=x<=4294967295."),   # ARGoS seeds 0 from the clock
    (["footprint", "x.elf", "--kilobot-flash", "-5"], "--kilobot-flash: -5 is not in the range x>=0."),
    (["sim", "uav", "--xi", "inf"], "--xi: inf is not a finite number."),
    # a bad type
    (["script", EXAMPLE, "--steps", "many"], "--steps: 'many' is not a valid integer range."),
    (["sim", "uav", "--drones", "x"], "--drones: 'x' is not a valid integer."),
    (["bounds", "energy", "--capacity", "full"], "--capacity: 'full' is not a valid float."),
    # an argument that is not what it must be
    (["plot", "uav", "/nonexistent/results", "-o", "out"], "RESULTS: Directory '/nonexistent/results' does not exist."),
    # an unknown verb, at the top and in a study group
    (["chekc"], "No such command 'chekc'. Did you mean 'check'?"),
    (["sim", "boat"], "No such command 'boat'."),
    (["sweep", "uav", "-o", "out", "extra"], "Got unexpected extra argument (extra)"),
]


@pytest.mark.parametrize("args,line", CASES, ids=[" ".join(a)[-60:] for a, _ in CASES])
def test_a_usage_error_is_one_line_and_exit_status_2(args, line, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)                   # a verb that did run would write here, not in the tree
    result = CliRunner().invoke(main, args)
    assert (result.exit_code, result.stdout, result.stderr) == (2, "", "swarmvm: error: %s\n" % line)


def leaf_commands(group=main, path=()):
    """(argument path, command) for every verb, the studies' subcommands included."""
    for name, command in sorted(group.commands.items()):
        if isinstance(command, click.Group):
            yield from leaf_commands(command, path + (name,))
        else:
            yield path + (name,), command


VERBS = [path for path, _command in leaf_commands()]


@pytest.mark.parametrize("verb", VERBS, ids=[" ".join(v) for v in VERBS])
def test_every_verb_says_an_unknown_option_in_one_line(verb):
    result = CliRunner().invoke(main, [*verb, "--no-such-option"])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == "swarmvm: error: --no-such-option: no such option\n"


@pytest.mark.parametrize("verb", VERBS, ids=[" ".join(v) for v in VERBS])
def test_help_still_prints_as_click_prints_it(verb):
    result = CliRunner().invoke(main, [*verb, "--help"])
    assert result.exit_code == 0 and result.stderr == ""
    assert result.stdout.startswith("Usage: ") and "Options:" in result.stdout


def test_version_and_the_help_of_a_bare_group_still_print():
    version = CliRunner().invoke(main, ["--version"])
    assert version.exit_code == 0 and version.stdout.startswith("swarmvm, version ")
    bare = CliRunner().invoke(main, ["sim"])          # click shows a group's help when no verb is given
    assert "Usage: " in bare.output and "Commands:" in bare.output
