"""Every input a fuzzer found, kept in tests/fuzz/regressions/<fuzzer>/, replayed without a fuzzer.

A case runs through the very function the fuzzer ran (tests/fuzz/readers.py, gen_target.py), so
the property it broke is checked again; a reader's case also goes through ``swarmvm check`` on
the command line (``check``; ``trace`` for a script), which must load it or refuse it with one
``swarmvm: error:`` line and exit status 2. The C runtime's cases (c_runtime/) run once each through the libFuzzer harness."""

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from fuzz import campaign, readers
from swarmvm.cli.commands import main

CASES = sorted(p for p in readers.REGRESSIONS.glob("*/*") if p.is_file())
SUFFIXES = {"yaml": ".yaml", "xml": ".xml", "xmd": ".xmd", "nza": ".nza", "lua": ".nza", "gen": ".gen", "svm": ".svm",
            "svm_runtime": ".svm", "script": ".txt"}


@pytest.fixture(scope="module", autouse=True)
def _input_files():
    """The readers write their inputs into a folder of this process: removed afterwards."""
    yield
    readers.cleanup()


def _id(path: Path) -> str:
    return "%s/%s" % (path.parent.name, path.name)


def test_there_are_cases_and_each_names_a_fuzzer():
    assert CASES
    assert {p.parent.name for p in CASES} <= set(campaign.FUZZERS)


@pytest.mark.parametrize("case", [p for p in CASES if p.parent.name in readers.READERS], ids=_id)
def test_reader_case_holds_the_property(case):
    readers.READERS[case.parent.name](case.read_bytes())


@pytest.mark.parametrize("case", [p for p in CASES if p.parent.name in SUFFIXES], ids=_id)
def test_reader_case_is_one_line_on_the_command_line(case, tmp_path):
    path = tmp_path / (case.stem + SUFFIXES[case.parent.name])
    path.write_bytes(case.read_bytes())
    if case.parent.name == "script":
        command = ["trace", str(readers.SCRIPT_SUPERVISOR), "--script", str(path)]
    else:
        command = ["check", str(path)]
    result = CliRunner().invoke(main, command)
    assert result.exit_code in (0, 2), result.output
    if result.exit_code == 2:
        assert result.stderr.startswith("swarmvm: error: %s" % path.name) or \
            result.stderr.startswith("swarmvm: error: %s" % path), result.stderr
        assert result.stderr.count("\n") == 1 and result.stderr[:-1].isprintable(), result.stderr


@pytest.mark.parametrize("case", [p for p in CASES if p.parent.name == campaign.CODEGEN], ids=_id)
def test_codegen_case_refuses_or_compiles(case):
    from fuzz import gen_target
    gen_target.check_regression(case.read_text(encoding="utf-8"))


def test_codegen_seeds_refuse_or_compile():
    """The seeds, as the fuzzer decodes them: between them, code compiled for every target
    (the check reaches the compilers)."""
    from fuzz import gen_target
    from swarmvm.targets import TARGETS
    compiled = set()
    for data in gen_target.seeds().values():
        compiled.update(gen_target.compile_input(data))
    assert compiled == set(TARGETS)


@pytest.mark.parametrize("build", sorted(campaign.C_BUILDS))
def test_c_runtime_cases_and_seeds_replay_clean(build, tmp_path):
    """Each build of the harness run once on each kept case and each seed image (so it runs
    on good images too, whether or not a case is kept): no sanitizer report, no invariant broken."""
    exe = campaign.build_c_fuzzer(tmp_path, build)
    inputs = [p for p in CASES if p.parent.name in campaign.C_BUILDS]
    for name, data in campaign.seeds(build).items():
        inputs.append(tmp_path / name)
        inputs[-1].write_bytes(data)
    log = tmp_path / "replay.log"
    with open(log, "w") as out:
        status = subprocess.run([str(exe), *map(str, inputs)], stdout=out, stderr=subprocess.STDOUT).returncode
    text = log.read_text()
    assert status == 0, text[-3000:]
    assert text.count("Executed ") == len(inputs), text[-3000:]
