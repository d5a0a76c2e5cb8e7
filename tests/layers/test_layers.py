"""Layers one way (issue 28, point 5): no import cycle, the studies on the typed API only, the
compiler's command line without the studies, and no import that changes the process beyond
loading modules."""

import json
import os
import re
import subprocess
import sys
import textwrap

from c_calls import call_graph
from imports import ROOT, cycles, import_graph, imported_names, module_files

# What the studies may import from the compiler: the typed API and the mechanisms every caller
# of it uses (its errors, the terminal's one-line output, the click option types, the one way
# files are written, the escaping of user text for the context it is written in: the studies'
# Markdown tables), and the subpackages that hold them (whose __init__ holds a docstring only).
PUBLIC = {"swarmvm", "swarmvm.api", "swarmvm.boundary", "swarmvm.boundary.errors", "swarmvm.boundary.terminal",
          "swarmvm.boundary.output", "swarmvm.boundary.escape", "swarmvm.cli", "swarmvm.cli.options"}

# The folders the package is installed from (pyproject.toml's package-dir).
SOURCE_FOLDERS = ("generator", "templates", "runtime_c", "runtime_cpp", "runtime_py", "studies")

EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"


def _run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120,
                          cwd=ROOT)


def test_the_tree_has_no_import_cycle():
    assert cycles(import_graph()) == []


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


# The C sources whose calls form the graph: the firmware (harnesses, QEMU boards) and the C
# runtime it links with.
C_FOLDERS = ("firmware", "runtime_c")


def test_no_two_c_files_call_each_other():
    files = sorted(path for folder in C_FOLDERS for path in (ROOT / folder).rglob("*.c"))
    graph = call_graph(files, ROOT)
    assert cycles(graph) == []
    assert "firmware/harness/platform_host.c" in graph["firmware/harness/svm_harness.c"]


def test_the_c_call_reader_finds_a_cycle(tmp_path):
    """A harness whose run the platform calls, and which calls the platform's output: the shape
    the conformance harness had. Static functions, prototypes, comments and strings are no calls."""
    (tmp_path / "harness.c").write_text(
        "void write_out(const char *text);\n"
        "int run(void)\n{\n    write_out(\"done()\");\n    return 0;\n}\n")
    (tmp_path / "platform.c").write_text(
        "int run(void);\nstatic int helper(void) { return 1; }\n"
        "void write_out(const char *text)\n{\n    (void)text; /* run() */\n}\n"
        "int main(void)\n{\n    return run() + helper();\n}\n")
    (tmp_path / "other.c").write_text("static int write_out(void) { return 0; }\nint done(void) { return write_out(); }\n")
    graph = call_graph(sorted(tmp_path.glob("*.c")), tmp_path)
    assert graph == {"harness.c": {"platform.c"}, "platform.c": {"harness.c"}, "other.c": set()}
    assert cycles(graph) == [["harness.c", "platform.c"]]


def test_the_studies_import_only_the_public_api():
    files = module_files()
    reached = {(name, other) for name, path in files.items() if name.startswith("swarmvm.studies")
               for other in imported_names(name, path, files)
               if other.startswith("swarmvm") and not other.startswith("swarmvm.studies")}
    assert sorted((name, other) for name, other in reached if other not in PUBLIC) == []
    assert ("swarmvm.studies.drone_delivery.controller", "swarmvm.api") in reached


def test_the_compiler_command_line_imports_no_study():
    run = _run("""
        import sys
        import swarmvm.cli.commands
        print(sorted(m for m in sys.modules if m.startswith("swarmvm.studies")))
    """)
    assert (run.returncode, run.stdout, run.stderr) == (0, "[]\n", "")


def test_every_compiler_verb_works_when_the_studies_cannot_be_imported(tmp_path):
    """The studies made unimportable: the main help, a verb's help and a verb's work are intact;
    a study verb is what fails."""
    run = _run("""
        import sys
        from importlib.abc import MetaPathFinder

        class NoStudies(MetaPathFinder):
            def find_spec(self, name, path=None, target=None):
                if name.startswith("swarmvm.studies"):
                    raise ImportError("studies blocked")

        sys.meta_path.insert(0, NoStudies())
        from swarmvm.cli.commands import main
        for args in (["--help"], ["gen", "--help"], ["check", %r], ["gen", %r, "-t", "c", "-o", %r]):
            try:
                main(args, prog_name="swarmvm")
            except SystemExit as exc:
                print("exit", exc.code)
        try:
            main(["sim", "--help"], prog_name="swarmvm")
        except ImportError as exc:
            print("sim:", exc)
    """ % (str(EXAMPLE), str(EXAMPLE), str(tmp_path / "c")))
    assert run.returncode == 0, run.stderr
    assert run.stdout.count("exit 0") == 4, run.stdout
    assert re.search(r"\n  gen +Generate a target's VM sources", run.stdout) and "Usage: swarmvm gen" in run.stdout
    assert "| %s |" % EXAMPLE in run.stdout and (tmp_path / "c" / "energy_worker_tables.c").is_file()
    assert "sim: studies blocked" in run.stdout


def test_the_study_verbs_list_and_run_their_subcommands():
    run = _run("""
        from swarmvm.cli.commands import main
        for verb in ("sim", "sweep", "plot", "bounds"):
            try:
                main([verb, "--help"], prog_name="swarmvm")
            except SystemExit:
                pass
        main(["bounds", "energy", "--json"], prog_name="swarmvm")
    """)
    assert run.returncode == 0, run.stderr
    assert run.stdout.count("  energy  ") == 4 and run.stdout.count("  uav     ") == 3
    assert '"work": ' in run.stdout.splitlines()[-1]


# Imports every module of the package, each in a fork of one interpreter that has imported
# nothing of swarmvm (a fresh interpreter each, at the cost of one start), and prints the modules
# an import left in sys.modules under a name other than the package's (swarmvm.*) that are files
# of this tree (the runtime registered as top-level modules, say; the standard library and
# third-party packages may load what they load), and whether it changed sys.path.
_SIDE_EFFECTS = """
import importlib, json, os, sys
folders, names, report = tuple(json.loads(sys.argv[1])), json.loads(sys.argv[2]), {}
for name in names:
    read, write = os.pipe()
    if os.fork() == 0:
        before, path = set(sys.modules), list(sys.path)
        importlib.import_module(name)
        foreign = sorted(m for m in set(sys.modules) - before if m != "swarmvm" and not m.startswith("swarmvm.")
                         and os.path.realpath(getattr(sys.modules[m], "__file__", None) or "/").startswith(folders))
        os.write(write, json.dumps([foreign, sys.path != path]).encode())
        os._exit(0)
    os.close(write)
    with os.fdopen(read) as pipe:
        report[name] = json.loads(pipe.read() or '["import failed", false]')
    os.wait()
print(json.dumps(report))
"""


def test_importing_a_module_of_the_package_changes_nothing_else():
    names = sorted(name for name in module_files() if name.startswith("swarmvm.") and name != "swarmvm.__main__")
    folders = [str(ROOT / folder) + os.sep for folder in SOURCE_FOLDERS]
    run = subprocess.run([sys.executable, "-c", _SIDE_EFFECTS, json.dumps(folders), json.dumps(names)],
                         capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert run.returncode == 0, run.stderr[-2000:]
    report = json.loads(run.stdout)
    assert len(report) == len(names) > 50
    assert {name: found for name, found in report.items() if found != [[], False]} == {}


def test_the_reference_vm_loads_without_registering_runtime_files():
    run = _run("""
        import sys
        from swarmvm.compiler.runtime_files import image_format, python_vm
        vm = python_vm()
        print(vm.ImageError is image_format().ImageError, vm.__name__,
              sorted(m for m in sys.modules if m.startswith("swarmvm_")))
    """)
    assert (run.returncode, run.stdout) == (0, "True swarmvm.runtime_py.swarmvm_vm []\n"), run.stderr
