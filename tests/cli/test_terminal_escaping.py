"""User text never reaches the terminal raw: whatever a file name, a key of a supervisor file, a
model or event name or an option value holds (ESC sequences, line breaks, CR, bidirectional
overrides, NUL), stdout and stderr hold no control character but their line ends, and stderr
holds exactly one line per message (so no forged ``swarmvm: error:`` line). Warnings, notes,
drift messages and echoed paths printed such text as it was."""

import tempfile
from pathlib import Path

import yaml
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from swarmvm.cli.commands import main

ROOT = Path(__file__).parents[2]
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
PUBLIC = ROOT / "tests" / "corpus" / "nadzoru2" / "public_example.yaml"

HOSTILE = ["\x1b[2J", "\x1b]0;owned\x07", "\n", "\r", "\nswarmvm: error: forged", "\r\x1b[K", "\u202e", "\x00",
           "\u2028", "\x85", "\t", "\x7f", "\x9b31m"]
ANY = st.characters(exclude_categories=("Cs",))                    # any character UTF-8 can encode
FILE_CHARACTER = st.characters(exclude_categories=("Cs",), exclude_characters="/\x00")


def planted(alphabet, hostile=HOSTILE):
    """Text of ``alphabet`` with one of the ``hostile`` sequences planted in it."""
    return st.builds(lambda a, h, b: a + h + b, st.text(alphabet, max_size=6), st.sampled_from(hostile),
                     st.text(alphabet, max_size=6))


TEXT = planted(ANY)
FILE_NAME = planted(FILE_CHARACTER, [h for h in HOSTILE if "/" not in h and "\x00" not in h])
SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def assert_escaped(result, messages):
    """No control character but line ends on either stream; ``messages`` lines on stderr, each a
    swarmvm message."""
    for stream in (result.stdout, result.stderr):
        assert all(c == "\n" or c.isprintable() for c in stream), repr(stream)
    lines = result.stderr.split("\n")
    assert lines.pop() == "" and len(lines) == messages, repr(result.stderr)
    assert all(line.startswith("swarmvm: ") for line in lines), repr(result.stderr)


def supervisor_with_key(folder: Path, file_name: str, key: str) -> Path:
    """The example supervisor with an unknown key, written as ``folder/file_name``."""
    document = yaml.safe_load(EXAMPLE.read_text())
    document["x" + key] = 1
    path = folder / file_name
    path.write_text(yaml.safe_dump(document))
    return path


@SETTINGS
@given(file_name=FILE_NAME, key=TEXT)
def test_check_warns_of_an_unknown_key_in_one_escaped_line(file_name, key):
    """Was: the key printed raw, so ``\\nswarmvm: error: forged`` made a second error line."""
    with tempfile.TemporaryDirectory() as folder:
        path = supervisor_with_key(Path(folder), file_name + ".yaml", key)
        result = run("check", path)
        assert result.exit_code == 0, result.stderr
        assert_escaped(result, 1)
        assert len(result.stdout.split("\n")) == 4                  # header, rule, one row, the last line end
        assert result.stdout.split("\n")[2].count(" | ") == 5        # a '|' in the name does not split the cell


@SETTINGS
@given(folder_name=FILE_NAME, key=TEXT)
def test_gen_echoes_paths_and_drifts_in_escaped_lines(folder_name, key):
    with tempfile.TemporaryDirectory() as folder:
        path = supervisor_with_key(Path(folder), "in.yaml", key)
        out = Path(folder) / folder_name
        first = run("gen", path, "-t", "python", "-o", out, "--name", "energy_worker")
        assert first.exit_code == 0, first.stderr
        assert_escaped(first, 1)
        assert len(first.stdout.split("\n")) == len(list(out.iterdir())) + 1     # one line per file written
        controller = out / "energy_worker_controller.py"
        controller.write_text(controller.read_text() + "\n    def on_gone(self, data):\n        pass\n")
        again = run("gen", path, "-t", "python", "-o", out, "--name", "energy_worker")
        assert again.exit_code == 0, again.stderr
        assert_escaped(again, 2)                                      # the unknown key, the drift
        assert "stale callbacks" in again.stderr.split("\n")[1]


@SETTINGS
@given(folder_name=FILE_NAME, file_name=FILE_NAME, key=TEXT)
def test_pack_and_export_echo_the_paths_they_wrote_in_one_line_each(folder_name, file_name, key):
    with tempfile.TemporaryDirectory() as folder:
        path = supervisor_with_key(Path(folder), "in.yaml", key)
        out = Path(folder) / folder_name
        out.mkdir()
        packed = run("pack", path, "-o", out / (file_name + ".svm"))
        assert packed.exit_code == 0, packed.stderr
        assert_escaped(packed, 1)
        assert packed.stdout.count("\n") == 1
        exported = run("export", path, "-f", "yaml", "-o", out / (file_name + ".yaml"))
        assert exported.exit_code == 0, exported.stderr
        assert_escaped(exported, 1)
        assert exported.stdout.count("\n") == 1


@SETTINGS
@given(name=TEXT)
def test_a_model_name_is_refused_or_used_in_escaped_lines(name):
    with tempfile.TemporaryDirectory() as folder:
        for verb in (["gen", EXAMPLE, "-t", "c"], ["export", EXAMPLE, "-f", "gen"]):
            result = run(*verb, "-o", Path(folder) / "out", "--name", name)
            assert result.exit_code in (0, 2)
            assert_escaped(result, 1 if result.exit_code else 0)


@SETTINGS
@given(event=TEXT)
def test_an_event_name_is_refused_in_one_escaped_line(event):
    document = yaml.safe_load(PUBLIC.read_text())
    old = document["events"][0]
    document["events"][0] = "EV_" + event
    document["sup_data"] = [document["events"][0] if item == old else item for item in document["sup_data"]]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "s.yaml"
        path.write_text(yaml.safe_dump(document))
        for verb in (["check"], ["pack", "-o", Path(folder) / "s.svm"]):
            result = run(*verb, path)
            assert result.exit_code == 2
            assert_escaped(result, 1)


@SETTINGS
@given(file_name=FILE_NAME)
def test_a_file_that_is_not_there_is_named_in_one_escaped_line(file_name):
    with tempfile.TemporaryDirectory() as folder:
        for verb in (["check"], ["script"], ["equiv", EXAMPLE], ["footprint"]):
            result = run(*verb, Path(folder) / file_name)
            assert result.exit_code == 2
            assert_escaped(result, 1)


@SETTINGS
@given(value=TEXT)
def test_option_values_and_verbs_are_echoed_in_one_escaped_line(value):
    value = "x" + value                  # never blank, never a number: float(" 1\t") is 1.0
    with tempfile.TemporaryDirectory() as folder:
        for args in (["check", EXAMPLE, "--" + value], ["gen", EXAMPLE, "-o", folder, "-t", value], [value],
                     ["sim", value], ["sweep", "uav", "-o", Path(folder) / "out", "--rules", value],
                     ["script", EXAMPLE, "--density", value], ["bounds", "energy", "--capacity", value]):
            result = run(*args)
            assert result.exit_code == 2, args
            assert_escaped(result, 1)
