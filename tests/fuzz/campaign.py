"""Run swarmvm's fuzzers for a given time each and report what they found (docs/fuzzing.md).

``python tests/fuzz/campaign.py [--seconds N] [--work DIR] [FUZZER...]``: every fuzzer by
default, the atheris targets (each reader of tests/fuzz/readers.py, and ``codegen``,
tests/fuzz/gen_target.py) and ``c_runtime``, the libFuzzer harness tests/fuzz/svm_fuzz.c over
the C runtime, built here with clang and AddressSanitizer and UndefinedBehaviorSanitizer
(``c_runtime_exact``: the same with a Kilobot-like build's exact masks and one-byte states).

Each fuzzer keeps its corpus in DIR/<fuzzer>/corpus (seeded on first use, grown by every run)
and its findings in DIR/<fuzzer>/findings, and its output in DIR/<fuzzer>/fuzz.log (a file,
not a pipe). Exit status 1 when a fuzzer found something or ran no input at all: a finding is
fixed, then its input is kept in tests/fuzz/regressions/<fuzzer>/. ``make fuzz`` runs this for
FUZZ_SECONDS each; tests/fuzz/test_fuzz_short.py runs it briefly in ``make test``."""

import argparse
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from fuzz import readers  # noqa: E402
from swarmvm.compiler.runtime_files import RUNTIME_C  # noqa: E402

C_RUNTIME = "c_runtime"
C_RUNTIME_EXACT = "c_runtime_exact"
CODEGEN = "codegen"
# The C harness's builds: the format's maxima as limits (every image the format allows fits),
# and a Kilobot-like build with exact masks (the unrolled step of SVM_MASK_EXACT, one-byte states).
C_BUILDS = {C_RUNTIME: readers.C_LIMITS,
            C_RUNTIME_EXACT: ["-DSVM_MAX_EVENTS=10", "-DSVM_MAX_SUPERVISORS=8", "-DSVM_MAX_STATES=256",
                              "-DSVM_MASK_EXACT=1"]}
FUZZERS = [*readers.READERS, CODEGEN, *C_BUILDS]
SANITIZE = ["-fsanitize=fuzzer,address,undefined", "-fno-sanitize-recover=all"]
TIMEOUTS = {CODEGEN: 120}       # seconds one input may take: compiling six targets is slow
TIMEOUT = 10
RSS_LIMIT_MB = 2048
# What libFuzzer leaves in -artifact_prefix for a finding (not its slow-unit-* notes).
FINDINGS = ("crash-", "timeout-", "oom-", "leak-")
RUNS = re.compile(r"^(?:Done (\d+) runs in|stat::number_of_executed_units: (\d+))", re.MULTILINE)


@dataclass(frozen=True)
class Result:
    """One fuzzer's run: inputs executed, the inputs it left as findings, its exit status."""
    fuzzer: str
    runs: int
    findings: list
    status: int
    log: Path

    def ok(self) -> bool:
        return self.status == 0 and not self.findings and self.runs > 0

    def summary(self) -> str:
        state = "ok" if self.ok() else "FINDING" if self.findings else "FAILED (exit %d)" % self.status
        found = "".join("\n    %s" % path for path in self.findings)
        return "%-16s %-8s %8d runs   %s%s" % (self.fuzzer, state, self.runs, self.log, found)


def build_c_fuzzer(out: Path, build: str = C_RUNTIME) -> Path:
    """The libFuzzer program over runtime_c/swarmvm.c, one of C_BUILDS (clang; Debian's
    libclang-rt-*-dev)."""
    exe = out / build
    out.mkdir(parents=True, exist_ok=True)
    subprocess.run(["clang", "-std=c99", "-g", "-O1", "-Wall", "-Wextra", "-Werror", "-pedantic", *SANITIZE,
                    *C_BUILDS[build], "-I", str(RUNTIME_C), str(HERE / "svm_fuzz.c"), str(RUNTIME_C / "swarmvm.c"),
                    "-o", str(exe)], check=True)
    return exe


def seeds(fuzzer: str) -> dict:
    """The seed corpus of a fuzzer ({file name: bytes}): the C runtime's are the images packed
    from the test corpus's supervisors, as the ``.svm`` readers'."""
    if fuzzer == CODEGEN:
        from fuzz import gen_target
        return gen_target.seeds()
    return readers.seeds("svm" if fuzzer in C_BUILDS else fuzzer)


# libFuzzer dictionaries (tests/fuzz/dicts): the keys and tokens of each input language.
DICTIONARIES = {"yaml": "yaml", "xml": "xml", "xmd": "xml", "nza": "nza", "lua": "nza", "gen": "gen", "script": "script"}


def command(fuzzer: str, work: Path) -> list:
    if fuzzer in C_BUILDS:
        return [str(build_c_fuzzer(work / fuzzer / "bin", fuzzer))]
    words = ["-dict=%s" % (HERE / "dicts" / (DICTIONARIES[fuzzer] + ".dict"))] if fuzzer in DICTIONARIES else []
    return [sys.executable, str(HERE / "run.py"), fuzzer, *words]


def run(fuzzer: str, seconds: int, work: Path) -> Result:
    """Fuzz ``fuzzer`` for about ``seconds`` (after its corpus has run once)."""
    folder = work / fuzzer
    corpus, findings = folder / "corpus", folder / "findings"
    for path in (corpus, findings):
        path.mkdir(parents=True, exist_ok=True)
    if not any(corpus.iterdir()):
        for name, data in seeds(fuzzer).items():
            (corpus / name).write_bytes(data)
    before = set(findings.iterdir())
    log = folder / "fuzz.log"
    with open(log, "w") as out:
        proc = subprocess.run([*command(fuzzer, work), "-max_total_time=%d" % seconds,
                               "-timeout=%d" % TIMEOUTS.get(fuzzer, TIMEOUT), "-rss_limit_mb=%d" % RSS_LIMIT_MB,
                               "-print_final_stats=1", "-artifact_prefix=%s/" % findings, str(corpus)],
                              stdout=out, stderr=subprocess.STDOUT)
    text = log.read_text(errors="replace")
    runs = max((int(a or b) for a, b in RUNS.findall(text)), default=0)
    found = sorted(p for p in set(findings.iterdir()) - before if p.name.startswith(FINDINGS))
    if fuzzer == CODEGEN:       # each with the supervisor it decodes to: the regression case to keep
        from fuzz import gen_target
        for path in list(found):
            found.append(path.with_suffix(".yaml"))
            found[-1].write_text(gen_target.regression_text(path.read_bytes()), encoding="utf-8")
    return Result(fuzzer, runs, found, proc.returncode, log)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fuzzers", nargs="*", metavar="FUZZER", help="which to run (default: all of %s)" % ", ".join(FUZZERS))
    parser.add_argument("--seconds", type=int, default=600, help="time per fuzzer (default 600)")
    parser.add_argument("--work", type=Path, default=Path("build/fuzz"), help="corpora, findings, logs")
    args = parser.parse_args(argv)
    for fuzzer in args.fuzzers:
        if fuzzer not in FUZZERS:
            parser.error("unknown fuzzer %r (one of %s)" % (fuzzer, ", ".join(FUZZERS)))
    results = [run(fuzzer, args.seconds, args.work.resolve()) for fuzzer in args.fuzzers or FUZZERS]
    for result in results:
        print(result.summary())
    return 0 if all(r.ok() for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
