"""The command line: check reproduces the corpus table (the seed's KPI rows), script and trace
agree with the reference VM, gen writes a runnable Python controller and never overwrites it."""

import re
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.readers.event_script import parse_script

CORPUS = Path(__file__).parent.parent / "corpus"


def corpus_table():
    """Rows of tests/corpus/README.md: file -> (events, supervisors, states, transitions, bytes)."""
    rows = {}
    for line in (CORPUS / "README.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 7 and cells[0].endswith(".yaml") and cells[2].isdigit():
            rows[cells[0]] = tuple(int(c) for c in cells[2:7])
    return rows


def test_check_prints_the_corpus_table_exactly(monkeypatch):
    monkeypatch.chdir(CORPUS / "openswarm")
    files = sorted(p.name for p in (CORPUS / "openswarm").glob("*.yaml"))
    result = CliRunner().invoke(main, ["check"] + files)
    assert result.exit_code == 0, result.stderr
    printed = {}
    for line in result.stdout.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        printed[re.sub(r"\\(.)", r"\1", cells[0])] = tuple(int(c) for c in cells[1:])    # Markdown-escaped names
    assert printed == corpus_table() and len(printed) == 8


def test_check_names_each_file_as_given_so_two_roles_rows_differ(tmp_path, monkeypatch):
    """Issue 40: the OpenSwarm layout keeps each role's supervisor.yaml in a folder of its own."""
    for role, source in (("worker", "network_worker.yaml"), ("leader", "network_leader.yaml")):
        (tmp_path / role).mkdir()
        (tmp_path / role / "supervisor.yaml").write_bytes((CORPUS / "openswarm" / source).read_bytes())
    monkeypatch.chdir(tmp_path)
    given = ["worker/supervisor.yaml", "./leader/supervisor.yaml", str(tmp_path / "worker" / "supervisor.yaml")]
    result = CliRunner().invoke(main, ["check", *given])
    assert result.exit_code == 0, result.stderr
    assert [line.split("|")[1].strip() for line in result.stdout.splitlines()[2:]] == given


def test_gen_names_a_supervisor_yaml_after_its_folder_and_says_so(tmp_path, monkeypatch):
    (tmp_path / "my-worker").mkdir()
    (tmp_path / "my-worker" / "supervisor.yaml").write_bytes((CORPUS / "openswarm" / "capbot_demo.yaml").read_bytes())
    monkeypatch.chdir(tmp_path / "my-worker")
    result = CliRunner().invoke(main, ["gen", "supervisor.yaml", "--target", "python", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.stderr
    assert result.stderr == ("swarmvm: note: named the model my_worker after the folder of supervisor.yaml "
                             "(give --name to choose another)\n")
    assert (tmp_path / "out" / "my_worker.svm").is_file()
    named = CliRunner().invoke(main, ["gen", "supervisor.yaml", "--target", "python", "-o", str(tmp_path / "o2"),
                                      "--name", "supervisor"])
    assert named.exit_code == 0 and named.stderr == "" and (tmp_path / "o2" / "supervisor.svm").is_file()


def test_script_then_trace_is_the_reference_trace(vm, tmp_path):
    path = str(CORPUS / "openswarm" / "hitl_leader.yaml")
    script = CliRunner().invoke(main, ["script", path, "--steps", "30", "--seed", "4"]).stdout
    (tmp_path / "s.txt").write_text(script)
    result = CliRunner().invoke(main, ["trace", path, "--script", str(tmp_path / "s.txt"), "--seed", "11",
                                       "--inputs", "edge", "--policy", "first"])
    assert result.exit_code == 0, result.stderr
    compiled = compile_inputs([path])
    rows = parse_script("s", script, compiled.model.events, compiled.tables.controllable)
    machine = vm.VM(compiled.image, inputs="edge", policy="first", seed=11)
    assert result.stdout.splitlines() == vm.replay(machine, rows)
    assert len(rows) == 30 and re.fullmatch(r"1 \S+ [0-9,]+ \d+", result.stdout.splitlines()[0])


def test_trace_refuses_a_controllable_event_in_the_script(tmp_path):
    (tmp_path / "s.txt").write_text("-\nEV_bid\n")
    result = CliRunner().invoke(main, ["trace", str(CORPUS / "openswarm" / "uav.yaml"), "--script", str(tmp_path / "s.txt")])
    assert result.exit_code == 2
    assert result.stderr == "swarmvm: error: %s: line 2: event EV_bid: controllable events are chosen by the VM, not scripted\n" % (tmp_path / "s.txt")


def test_generated_python_controller_runs_and_is_never_overwritten(tmp_path):
    args = ["gen", str(CORPUS / "openswarm" / "uav.yaml"), "--target", "python", "-o", str(tmp_path)]
    assert CliRunner().invoke(main, args).exit_code == 0
    controller = tmp_path / "uav_controller.py"
    source = controller.read_text()
    assert "def check_capableTask(self, data):" in source and "def on_bid(self, data):" in source
    edited = source.replace("def check_capableTask(self, data):\n", "def check_capableTask(self, data):\n        return True\n")
    controller.write_text(edited)
    assert CliRunner().invoke(main, args).exit_code == 0
    assert controller.read_text() == edited
    run = subprocess.run([sys.executable, "-c", "import uav_app as c\nvm = c.make_vm()\n"
                          "print([vm.image.event_name(e) for e in vm.step()])"],
                         cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "['EV_capableTask', 'EV_bid']"


def test_generated_table_modules_import_for_every_corpus_supervisor(tmp_path):
    """Every corpus supervisor (public inputs, empty names, probabilities) gives a table module
    Python can import, whose constants match the image, and whose compiled-in image is the very
    bytes of the loadable .svm (so compiled-in and loaded runs are the same run)."""
    for path in sorted(CORPUS.glob("*/*.yaml")):
        out = tmp_path / path.stem
        assert CliRunner().invoke(main, ["gen", str(path), "--target", "python", "-o", str(out)]).exit_code == 0
        run = subprocess.run([sys.executable, "-c", "import %s_tables as t, swarmvm_vm as v\n"
                              "i = v.Image.parse(t.IMAGE)\n"
                              "assert [getattr(t, n) for n in t.EVENTS] == list(range(i.num_events))\n"
                              "assert list(t.EVENTS) == [i.event_name(e) for e in range(i.num_events)]\n"
                              "assert t.IMAGE == open('%s.svm', 'rb').read()" % (path.stem, path.stem)],
                             cwd=out, capture_output=True, text=True)
        assert run.returncode == 0, (path.name, run.stderr)
