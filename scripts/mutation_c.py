"""`make mutation-c` (docs/mutation.md): mutation testing of the C runtime, runtime_c/swarmvm.c,
judged by the quick host tests that compile it (conformance, reader parity, the fuzz harness on
its seeds), then the report (scripts/mutation_report.py).

No mutation tool for C is installed, so the mutants come from scripts/c_mutants.py. Like
scripts/mutation.py (whose copy of the tree and environment probe this reuses), it never touches
the checkout: each mutant is written into WORK/tree/runtime_c/swarmvm.c and the tests run in that
copy. A mutant costs one test run at most: one that no host build compiles (AVR-only code, an
option the judge leaves on) is "unreached" and not run; one the compiler refuses under the
project's warnings is "stillborn" (gcc -fsyntax-only first, a fraction of a second); both are left
out of the kill rate. Results are appended to WORK/results.jsonl as they come, each with the
digest of the unmutated source, so an interrupted run resumes where it stopped."""

import argparse
import hashlib
import json
import os
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import c_mutants
import mutation

ROOT = mutation.ROOT
MODULE = "runtime_c/swarmvm.c"
# The quick host tests that compile swarmvm.c. The conformance builds come first: half a second
# each, they kill most mutants; the kills written against the survivors come last, as they
# only matter to mutants the others let through.
JUDGE = ["tests/conformance/test_c_host.py", "tests/compiler/test_reader_parity.py", "tests/compiler/test_image_stream.py",
         "tests/compiler/test_format_constants.py",
         "tests/fuzz/test_fuzz_regressions.py::test_c_runtime_cases_and_seeds_replay_clean",
         "tests/mutation_kills_c/test_c_runtime_kills.py"]
# The limits the judge's builds compile swarmvm.c with (each selects other code: a mask of 1, 2
# or 4 bytes, 64 bits, a byte array, exact widths): a mutant none of them compiles is unreached.
HOST_BUILDS: tuple[tuple[str, ...], ...] = (
    (), ("-DSVM_MAX_EVENTS=8",), ("-DSVM_MAX_EVENTS=16",), ("-DSVM_MAX_EVENTS=24",),
    ("-DSVM_MAX_EVENTS=255", "-DSVM_MAX_SUPERVISORS=255", "-DSVM_MAX_STATES=65535"),
    ("-DSVM_MAX_EVENTS=10", "-DSVM_MASK_EXACT=1"))
# The project's warnings (tests/conformance/c_harness.py WARNINGS): a mutant they refuse never builds.
WARNINGS = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic")
TIMEOUT_FACTOR = 3


def preprocessed(path: Path, defines: tuple[str, ...]) -> str:
    """``path`` as the compiler sees it under ``defines``: what a mutant must change to be compiled."""
    return subprocess.run(["gcc", "-E", "-P", *WARNINGS, *defines, "-I", str(path.parent), str(path)],
                          check=True, capture_output=True, text=True).stdout


def reaching_builds(path: Path, originals: dict[tuple[str, ...], str]) -> list[tuple[str, ...]]:
    """The builds (keys of ``originals``, their unmutated preprocessed text) whose compiler sees
    the mutant now at ``path``: none when it lies in a branch all of them drop (AVR-only code)."""
    return [defines for defines, text in originals.items() if preprocessed(path, defines) != text]


def compiles(path: Path, builds: list[tuple[str, ...]]) -> bool:
    """Whether gcc accepts ``path`` under the project's warnings in each of ``builds``."""
    return all(subprocess.run(["gcc", "-fsyntax-only", *WARNINGS, *defines, "-I", str(path.parent), str(path)],
                              capture_output=True).returncode == 0 for defines in builds)


def running_in_group(pgid: int) -> list[int]:
    """The processes of process group ``pgid`` that have not died (a zombie awaiting its reaping
    has), from /proc/<pid>/stat: its state, then its group, after the command name's ')'."""
    alive = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue        # gone while being read
        if int(fields[2]) == pgid and fields[0] not in ("Z", "X"):
            alive.append(int(stat.parent.name))
    return alive


def kill_group(pgid: int, limit: float = 10.0) -> None:
    """SIGKILL to every process of the group, and back only once none runs: the signal is
    delivered asynchronously, so a program the tests started may still be running just after
    killpg returns. RuntimeError if some still run after ``limit`` seconds."""
    os.killpg(pgid, signal.SIGKILL)
    deadline = time.monotonic() + limit
    while running_in_group(pgid):
        if time.monotonic() > deadline:
            raise RuntimeError("mutation_c: processes %s of a killed judge still run" % running_in_group(pgid))
        time.sleep(0.01)


def judge(command: str, tree: Path, env: dict[str, str], timeout: float) -> str:
    """killed, timeout or survived: what the judge's tests make of the copy as it is now. The
    tests run in a session of their own, killed whole at the timeout: a mutant that makes a
    harness loop would otherwise leave it running, orphaned, after pytest is killed."""
    with subprocess.Popen(shlex.split(command), cwd=tree, env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, start_new_session=True) as tests:
        try:
            code = tests.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            kill_group(tests.pid)
            tests.wait()
            return "timeout"
    return "survived" if code == 0 else "killed"


def done_results(results: Path, digest: str, survivors: bool) -> dict[str, dict]:
    """{id: record} of the mutants of this source (``digest``) already run, the last record of
    each; survivors left out with ``survivors`` (run again against tests written since)."""
    if not results.exists():
        return {}
    records = (json.loads(line) for line in results.read_text(encoding="utf-8").splitlines() if line.strip())
    done = {r["id"]: r for r in records if r["digest"] == digest}
    return {k: r for k, r in done.items() if not (survivors and r["outcome"] == "survived")}


def run(work: Path, every: int, survivors: bool) -> dict[str, dict]:
    """Run the mutants whose number is a multiple of ``every`` and not yet in WORK/results.jsonl;
    {id: record} of the chosen mutants' results."""
    tree = mutation.copy_tree(work)
    env = mutation.environment(work, tree)
    target = tree / MODULE
    source = target.read_text(encoding="utf-8")
    digest = hashlib.sha256(source.encode()).hexdigest()[:16]
    results = work / "results.jsonl"
    done = done_results(results, digest, survivors)
    originals = {defines: preprocessed(target, defines) for defines in HOST_BUILDS}
    # Survivors judged again meet the kills written against them first: most die in seconds.
    command = mutation.test_command(JUDGE[-1:] + JUDGE[:-1] if survivors else JUDGE)
    took = mutation.baseline(command, tree, env)
    timeout = max(10.0, TIMEOUT_FACTOR * took)
    everyone = c_mutants.mutants(source)
    chosen = [m for m in everyone if int(m.id[1:]) % every == 0]
    todo = [m for m in chosen if m.id not in done]
    print("mutation-c: %d mutants, %d chosen (1 in %d), %d to run; judge %.1f s unmutated, timeout %.0f s"
          % (len(everyone), len(chosen), every, len(todo), took, timeout), flush=True)
    started = time.monotonic()
    try:
        with results.open("a", encoding="utf-8") as log:
            for n, m in enumerate(todo, 1):
                clock = time.monotonic()
                target.write_text(m.apply(source), encoding="utf-8")
                builds = reaching_builds(target, originals)
                if not builds:
                    outcome = "unreached"
                elif not compiles(target, builds):
                    outcome = "stillborn"
                else:
                    outcome = judge(command, tree, env, timeout)
                text, mutated = m.lines(source)
                record = {"id": m.id, "digest": digest, "module": MODULE, "operator": m.operator, "line": m.line,
                          "column": m.column, "text": text, "mutated": mutated, "outcome": outcome,
                          "seconds": round(time.monotonic() - clock, 1)}
                log.write(json.dumps(record) + "\n")
                log.flush()
                done[m.id] = record
                print("mutation-c: %d/%d %s line %d %s: %s" % (n, len(todo), m.id, m.line, m.operator, outcome),
                      flush=True)
    finally:
        target.write_text(source, encoding="utf-8")
    print("mutation-c: ran %d mutants in %.0f s" % (len(todo), time.monotonic() - started), flush=True)
    return {k: r for k, r in done.items() if int(k[1:]) % every == 0}


def write_mutants(work: Path, records: dict[str, dict]) -> None:
    """WORK/<slug>.mutants.json, scripts/mutation_report.py's input: the mutants the judge ran
    (unreached and stillborn ones are not in the rate; their count is printed)."""
    judged = [{key: r[key] for key in ("module", "operator", "line", "column", "text", "mutated", "outcome")}
              for _, r in sorted(records.items()) if r["outcome"] not in ("unreached", "stillborn")]
    (work / (mutation.slug(MODULE) + ".mutants.json")).write_text(json.dumps(judged, indent=1) + "\n",
                                                                  encoding="utf-8")
    counts: dict[str, int] = {}
    for r in records.values():
        counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    print("mutation-c: %s" % ", ".join("%s %d" % item for item in sorted(counts.items())), flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", type=Path, default=ROOT / "build" / "mutation-c")
    parser.add_argument("--every", type=int, default=1, metavar="K",
                        help="run 1 mutant in K (those whose number is a multiple of K): a sample, reported as such")
    parser.add_argument("--survivors", action="store_true",
                        help="run the survivors again (after writing tests against them)")
    args = parser.parse_args(argv)
    if args.every < 1:
        parser.error("--every must be 1 or more")
    work = args.work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    write_mutants(work, run(work, args.every, args.survivors))
    report = subprocess.run([sys.executable, str(ROOT / "scripts" / "mutation_report.py"), str(work),
                             "--equivalents", str(ROOT / "tests" / "mutation" / "equivalents.toml")])
    return report.returncode


if __name__ == "__main__":
    sys.exit(main())
