"""Every option of every verb says what it does, and every default is shown the same way
(issue 27): `script --steps`, `trace --seed` and others had no description, the energy verbs
showed defaults as `(100)` where the others show `100.0`, `--work-rate` took 0 in `sim energy`
and not in `bounds energy`, and `gen --help` named only Nadzoru 2 XML among its inputs."""

import re

import click
import pytest
from click.testing import CliRunner

from cli.test_usage_errors import VERBS, leaf_commands
from swarmvm.cli.commands import main

OPTIONS = [(path, option) for path, command in leaf_commands() for option in command.params
           if isinstance(option, click.Option)]


def has_default(option: click.Option) -> bool:
    """A default a user may not give: a value, not None or click's unset marker, nor a flag's."""
    return isinstance(option.default, (int, float, str)) and not option.is_flag


@pytest.mark.parametrize("path,option", OPTIONS, ids=["%s %s" % (" ".join(p), o.opts[-1]) for p, o in OPTIONS])
def test_every_option_has_help_text_and_shows_its_default(path, option):
    assert (option.help or "").strip(), "%s %s has no help text" % (" ".join(path), option.opts[-1])
    if has_default(option):
        assert option.show_default is True, "%s %s hides its default" % (" ".join(path), option.opts[-1])


@pytest.mark.parametrize("verb", VERBS, ids=[" ".join(v) for v in VERBS])
def test_no_verb_shows_a_numeric_default_in_parentheses(verb):
    text = CliRunner().invoke(main, [*verb, "--help"], terminal_width=200).stdout
    assert not re.search(r"\[default: \(\d", text)


def range_shown(verb, option):
    text = CliRunner().invoke(main, [*verb, "--help"], terminal_width=200).stdout
    return re.search(re.escape(option) + r" FLOAT .*\[default: [^;]*; ([^\]]*)\]", text).group(1)


def test_work_rate_is_the_same_option_in_sim_and_bounds_energy():
    assert range_shown(["sim", "energy"], "--work-rate") == range_shown(["bounds", "energy"], "--work-rate") == "x>0"
    for verb in (["sim", "energy"], ["bounds", "energy"]):
        result = CliRunner().invoke(main, [*verb, "--work-rate", "0"])
        assert (result.exit_code, result.stderr) == (2, "swarmvm: error: --work-rate: 0.0 is not in the range x>0.\n")


def test_gen_help_names_every_input_format():
    text = CliRunner().invoke(main, ["gen", "--help"], terminal_width=200).stdout
    for suffix in (".yaml", ".xml", ".xmd", ".nza", ".gen"):
        assert suffix in text
