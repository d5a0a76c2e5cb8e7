"""`make mutation` (docs/mutation.md): cosmic-ray over the core modules, each with the quick tests
that cover it, then the report (scripts/mutation_report.py).

cosmic-ray mutates a module's file in place, runs the tests and puts the file back. So it never
works on the checkout: the tree is copied to WORK/tree (sources, tests, examples; no build output,
no venv, no caches) and a package folder WORK/site/swarmvm is made of links into that copy, laid out
as the installed package is (pyproject.toml's package-dir), first on PYTHONPATH, so that the tests
import the copy, the mutated file included, and never the editable install's checkout.

Modules, their tests and the operators used are in tests/mutation/modules.toml.

``--survivors`` re-runs only the mutants that survived a module's last session in WORK (the loop
of writing kill tests: minutes instead of an hour), the others keeping their outcome: a mutant the
tests killed stays killed as tests are added. It is refused when the module's text changed since
that session (its SHA-256 is kept beside it), since its mutants would no longer be the same."""

import argparse
import hashlib
import json
import os
import shlex
import shutil
import sqlite3
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import mutation_report

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "tests" / "mutation" / "modules.toml"
EQUIVALENTS = ROOT / "tests" / "mutation" / "equivalents.toml"
# Left out of the copy: what a build, a venv, git or a test run leaves, and earlier mutation runs.
IGNORED = shutil.ignore_patterns("build", ".venv", ".git", "__pycache__", "*.pyc", ".pytest_cache", ".hypothesis",
                                 "*.egg-info", "mutants", ".swarmvm-*")
# The installed package's folders (pyproject.toml's package-dir) other than generator/ itself.
PACKAGE_DIRS = ("templates", "runtime_c", "runtime_cpp", "runtime_py", "studies")


def copy_tree(work: Path) -> Path:
    """A fresh copy of the checkout at WORK/tree and the package layout at WORK/site; the copy."""
    work = work.resolve()
    tree, site = work / "tree", work / "site"
    for folder in (tree, site):
        if folder.exists():
            shutil.rmtree(folder)
    shutil.copytree(ROOT, tree, ignore=IGNORED, symlinks=True)
    package = site / "swarmvm"
    package.mkdir(parents=True)
    for entry in (tree / "generator").iterdir():
        (package / entry.name).symlink_to(entry)
    for folder in PACKAGE_DIRS:
        (package / folder).symlink_to(tree / folder)
    return tree


def environment(work: Path, tree: Path) -> dict[str, str]:
    """The tests' environment: the copy first on the import path, no bytecode written (a mutant
    written within the second its original was compiled would otherwise run as the original).
    SystemExit unless the package and both runtime modules then import from the copy."""
    env = dict(os.environ, PYTHONPATH=str(work.resolve() / "site"), PYTHONDONTWRITEBYTECODE="1")
    probe = ("from swarmvm.compiler import runtime_files as runtime\n"
             "print(runtime.__file__, runtime.image_format().__file__, runtime.python_vm().__file__, sep='\\n')")
    found = subprocess.run([sys.executable, "-c", probe], cwd=tree, env=env, capture_output=True, text=True).stdout
    if not found or any(not path.startswith(str(work.resolve())) for path in found.split()):
        sys.exit("mutation: the tests would not import the copy in %s:\n%s" % (work, found))
    return env


def test_command(tests: list[str]) -> str:
    return shlex.join([sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
                       "-m", "not emulator and not slow", *tests])


def excluded_operators(kept: list[str]) -> list[str]:
    """cr-filter-operators' exclusion: every operator but the ``kept`` ones."""
    return ["^(?!core/(%s)$)" % "|".join(kept)]


def slug(module: str) -> str:
    return module.replace("/", "__").removesuffix(".py")


def baseline(command: str, tree: Path, env: dict[str, str]) -> float:
    """Seconds the unmutated module's tests take; SystemExit when they fail (every mutant would
    then count as killed)."""
    started = time.monotonic()
    run = subprocess.run(shlex.split(command), cwd=tree, env=env, capture_output=True, text=True)
    if run.returncode:
        sys.exit("mutation: the tests fail on the unmutated copy:\n%s\n%s" % (command, run.stdout[-4000:]))
    return time.monotonic() - started


def forget_survivors(session: Path, module: str, source: list[str], equivalents: set[tuple[str, str, str, int]]) -> int:
    """Drop the results of the session's surviving (and unrunnable) mutants of ``module`` (its
    lines ``source``) but those marked equivalent, so that ``cosmic-ray exec`` runs them again; how
    many. (cosmic-ray keeps one row of work_results per mutant run, and exec runs the mutants
    without one; an equivalent mutant would only survive again.)"""
    with sqlite3.connect(session) as db:
        rows = db.execute("SELECT job_id, operator_name, start_pos_row, start_pos_col FROM work_results "
                          "JOIN mutation_specs USING (job_id) WHERE test_outcome IN ('SURVIVED', 'INCOMPETENT')")
        again = [(job,) for job, operator, row, column in rows.fetchall()
                 if (module, operator, source[row - 1].strip(), column) not in equivalents]
        db.executemany("DELETE FROM work_results WHERE job_id = ?", again)
    return len(again)


def run_module(module: str, tests: list[str], kept: list[str], work: Path, tree: Path, env: dict[str, str],
               survivors: bool = False) -> None:
    """Init, filter and execute one module's cosmic-ray session (with ``survivors``, re-execute
    its last session's survivors), then record its mutants as WORK/<slug>.mutants.json
    (scripts/mutation_report.py's input)."""
    name = slug(module)
    config, session = work / (name + ".toml"), work / (name + ".sqlite")
    digest, digest_file = hashlib.sha256((tree / module).read_bytes()).hexdigest(), work / (name + ".sha256")
    if survivors and (not session.exists() or not digest_file.exists() or digest_file.read_text() != digest):
        sys.exit("mutation: %s changed since its last session in %s, or has none: run it without --survivors"
                 % (module, work))
    command = test_command(tests)
    took = baseline(command, tree, env)
    config.write_text("[cosmic-ray]\nmodule-path = %s\ntimeout = %.1f\nexcluded-modules = []\ntest-command = %s\n\n"
                      "[cosmic-ray.distributor]\nname = \"local\"\n\n[cosmic-ray.filters.operators-filter]\n"
                      "exclude-operators = %s\n"
                      % (json.dumps(str(tree / module)), max(30.0, 5 * took), json.dumps(command),
                         json.dumps(excluded_operators(kept))), encoding="utf-8")
    started = time.monotonic()
    bin_dir = Path(sys.executable).parent
    steps = [[bin_dir / "cosmic-ray", "exec", config, session]]
    if survivors:
        source = (tree / module).read_text(encoding="utf-8").splitlines()
        equivalents = set(mutation_report.load_equivalents(EQUIVALENTS))
        print("mutation: %s: running its %d survivors again (those marked equivalent left out)"
              % (module, forget_survivors(session, module, source, equivalents)), flush=True)
    else:
        session.unlink(missing_ok=True)
        digest_file.write_text(digest)
        steps[:0] = [[bin_dir / "cosmic-ray", "init", config, session], [bin_dir / "cr-filter-operators", session, config]]
    for step in steps:
        subprocess.run([str(part) for part in step], cwd=tree, env=env, check=True)
    dump = subprocess.run([str(bin_dir / "cosmic-ray"), "dump", str(session)], cwd=tree, env=env, check=True,
                          capture_output=True, text=True).stdout
    mutants = mutants_of(module, (tree / module).read_text(encoding="utf-8").splitlines(), dump)
    (work / (name + ".mutants.json")).write_text(json.dumps(mutants, indent=1) + "\n", encoding="utf-8")
    print("mutation: %s: %d mutants, %.0f s (tests %.1f s each)" % (module, len(mutants), time.monotonic() - started,
                                                                      took), flush=True)


def mutants_of(module: str, source: list[str], dump: str) -> list[dict]:
    """The mutants of a ``cosmic-ray dump`` (JSON lines of [work item, result]) that ran, as
    scripts/mutation_report.py reads them; those the operator filter skipped are left out."""
    mutants = []
    for line in dump.splitlines():
        item, result = json.loads(line)
        if result is None or result["worker_outcome"] == "skipped":
            continue
        mutation = item["mutations"][0]
        row, column = mutation["start_pos"]
        if result["worker_outcome"] != "normal" or result["test_outcome"] == "incompetent":
            outcome = "incompetent"
        elif result["test_outcome"] == "survived":
            outcome = "survived"
        else:
            outcome = "timeout" if result["output"] == "timeout" else "killed"
        mutants.append({"module": module, "operator": mutation["operator_name"], "line": row, "column": column,
                        "text": source[row - 1].strip(), "mutated": mutated_line(result.get("diff") or ""),
                        "outcome": outcome})
    return sorted(mutants, key=lambda m: (m["line"], m["column"], m["operator"]))


def mutated_line(diff: str) -> str:
    """The first line a mutant's unified diff adds, stripped."""
    added = [line[1:].strip() for line in diff.splitlines() if line.startswith("+") and not line.startswith("+++")]
    return added[0] if added else ""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", type=Path, default=ROOT / "build" / "mutation")
    parser.add_argument("--module", action="append", help="only this module (repeatable); default: all")
    parser.add_argument("--survivors", action="store_true",
                        help="re-run only the mutants that survived each module's last session in WORK")
    args = parser.parse_args(argv)
    config = tomllib.loads(CONFIG.read_text(encoding="utf-8"))
    modules = config["modules"]
    chosen = args.module or list(modules)
    unknown = sorted(set(chosen) - set(modules))
    if unknown:
        parser.error("not a module of %s: %s" % (CONFIG.relative_to(ROOT), ", ".join(unknown)))
    work = args.work.resolve()      # absolute: cosmic-ray runs in the copy, not where --work was given
    work.mkdir(parents=True, exist_ok=True)
    tree = copy_tree(work)
    env = environment(work, tree)
    for module in chosen:
        run_module(module, modules[module]["tests"], config["operators"]["kept"], work, tree, env, args.survivors)
    report = subprocess.run([sys.executable, str(ROOT / "scripts" / "mutation_report.py"), str(work),
                             "--equivalents", str(EQUIVALENTS)])
    return report.returncode


if __name__ == "__main__":
    sys.exit(main())
