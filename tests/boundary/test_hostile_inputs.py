"""Hostile and unusual input (issue 12's observed defects): each gives one line naming the file
and key, exit status 2 and nothing written, at once (no traceback, no hang)."""

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

CORPUS = Path(__file__).resolve().parents[1] / "corpus"
WORKER = (CORPUS / "openswarm" / "energy_worker.yaml").read_text()
PROBABILISTIC = (CORPUS / "nadzoru2" / "probabilistic_example.yaml").read_text()
XML_PLANT = next(CORPUS.glob("synthesis/energy_worker/*.xml")).read_text()


def with_probability(text):
    return PROBABILISTIC.replace("0.70000000", text, 1)


def gen_with_events(count):
    """A libFAUDES .gen automaton with ``count`` self-loop events."""
    events = " ".join("e%d" % i for i in range(count))
    loops = "\n".join("s0 e%d s0" % i for i in range(count))
    return ("<Generator>\n\"many\"\n<Alphabet>\n%s\n</Alphabet>\n<States>\ns0\n</States>\n<TransRel>\n%s\n"
            "</TransRel>\n<InitStates>\ns0\n</InitStates>\n<MarkedStates>\ns0\n</MarkedStates>\n</Generator>\n"
            % (events, loops))


CASES = {
    "deep_nesting.yaml": ("a: " + "[" * 50000 + "]" * 50000 + "\n",
                          "not a supervisor: lists or mappings nested too deeply"),
    "huge_integer.yaml": (WORKER.replace("num_supervisors: ", "num_supervisors: " + "9" * 5000 + "\nold_count: ", 1),
                          "num_supervisors: value of 5000 digits out of range"),
    "probability_over_zero.yaml": (with_probability("1/0"), "is not a probability in [0, 1]"),
    "probability_tiny_exponent.yaml": (with_probability("1e-100000000"), "is not a probability in [0, 1]"),
    "name_with_newline.yaml": (WORKER.replace("EV_moveToCharge", '"EV_a\\nb"', 1),
                               "events[0]: 'EV_a\\nb' is not an event name"),
    "name_with_nul.yaml": (WORKER.replace("EV_moveToCharge", '"EV_a\\0b"', 1), "events[0]: 'EV_a\\x00b' is not an event name"),
    "name_of_300.yaml": (WORKER.replace("EV_moveToCharge", "EV_" + "a" * 300), "is not an event name (at most 255"),
    "billion_laughs.yaml": ("a: &a [x, x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
                            "c: [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\n",
                            "not valid YAML at line 2: aliases (*name) are not accepted"),
    "events_300.gen": (gen_with_events(300), "300 events, over the image format's limit of 255"),
    "deep_nesting.xml": ('<model type="FSA"><data>' + "<x>" * 100000 + "</x>" * 100000 + "</data></model>\n",
                         "state: the automaton has no states"),
    "not_utf8.yaml": (b"num_events: 1\n\xff\n", "not UTF-8 text (byte 14)"),
    "superscript_id.xml": (re.sub(r'source="(\d+)"', 'source="²"', XML_PLANT, count=1),
                           "source: transition: expected a non-negative integer id of at most 9 digits, got '²'"),
    # A key given twice: the last value silently won (issue 23); "x" and x are the same key.
    "duplicate_key.yaml": (WORKER + '"sup_init_state": [ 1,0,0,0 ]\n',
                           "sup_init_state: line %d: key given twice (first at line 6)" % (WORKER.count("\n") + 1)),
    "duplicate_nested_key.yaml": (WORKER + "extra: {a: 1, b: 2, a: 3}\n",
                                  "a: line %d: key given twice (first at line %d)" % ((WORKER.count("\n") + 1,) * 2)),
}


@pytest.mark.parametrize("name", CASES)
def test_hostile_input_is_one_line(name, tmp_path):
    text, message = CASES[name]
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["gen", str(path), "--target", "c", "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("swarmvm: error: ") and name in result.stderr
    assert message in result.stderr
    assert not out.exists()


def test_a_script_that_is_not_utf8_is_one_line(tmp_path):
    script = tmp_path / "bad.script"
    script.write_bytes(b"EV_lowEnergy\n\xff\xfe\n")
    example = CORPUS / "openswarm" / "energy_worker.yaml"
    result = CliRunner().invoke(main, ["trace", str(example), "--script", str(script)])
    # trace streams a script file line by line, so the error names the line and the byte in it
    assert result.exit_code == 2 and result.stderr == "swarmvm: error: %s: line 2: not UTF-8 text (byte 0 of the line)\n" % script


def test_a_script_that_is_a_folder_is_one_line(tmp_path):
    example = CORPUS / "openswarm" / "energy_worker.yaml"
    for command in (["trace", str(example), "--script", str(tmp_path)], ["synth", "--script", str(tmp_path), "-o",
                                                                          str(tmp_path / "x.yaml"), str(example)]):
        result = CliRunner().invoke(main, command)
        assert result.exit_code == 2 and result.stderr == "swarmvm: error: %s: is a folder, not a regular file\n" % (
            tmp_path), command
