"""What swarmvm says to a user who installed the wheel names nothing that only the repository has
(issue 27, point 4: `run scripts/argos.sh`, `docs/*.md` in `--help`): every verb's and
sub-verb's help as click renders it, and every string the installed package's code holds that is
not a docstring (messages, errors, notes, report text). Docstrings of functions that are not
commands are for the code's readers, who have the repository; a command's docstring is its help,
and is read through the rendered help."""

import ast
import importlib
import re
from pathlib import Path

import click
import pytest

from swarmvm.cli.commands import main

# Top-level folders of the repository that the wheel does not install.
REPOSITORY_ONLY = re.compile(r"\b(scripts|docs|tests|benchmarks|firmware|examples|mk)/")
INSTALLED = ("swarmvm", "swarmvm.studies", "swarmvm.runtime_py")


def commands(group=main, path=("swarmvm",)):
    """(command line, command) of every verb and sub-verb, the group itself included."""
    yield " ".join(path), group
    if isinstance(group, click.Group):          # the studies' verbs load their sub-verbs on demand
        with click.Context(group) as context:
            for name in group.list_commands(context):
                yield from commands(group.get_command(context, name), path + (name,))


@pytest.mark.parametrize("line, command", list(commands()), ids=lambda v: v if isinstance(v, str) else "")
def test_help_names_no_repository_file(line, command):
    with click.Context(command, info_name=line) as context:
        text = command.get_help(context)
    assert not REPOSITORY_ONLY.findall(text), text


def messages(path):
    """(line, text) of every string constant of a Python file that is not a docstring."""
    tree = ast.parse(path.read_text())
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                  and node.body and isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant)}
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings]


def installed_sources():
    for package in INSTALLED:
        yield from sorted(Path(importlib.import_module(package).__file__).parent.rglob("*.py"))


def test_messages_name_no_repository_file():
    """A message may name a repository file where it says that a source checkout is what it needs."""
    found = ["%s:%d: %s" % (path.name, line, text) for path in installed_sources() for line, text in messages(path)
             if REPOSITORY_ONLY.search(text) and "source checkout" not in text]
    assert found == []


def test_the_scan_sees_what_it_must():
    """The two scans find the kind of text they are for (not an empty set of files or verbs)."""
    assert {line for line, _ in commands()} >= {"swarmvm", "swarmvm gen", "swarmvm sim energy", "swarmvm sweep uav"}
    texts = [text for path in installed_sources() if path.name == "plugin.py" for _, text in messages(path)]
    assert any(text.startswith("ARGoS 3 not found") for text in texts)
