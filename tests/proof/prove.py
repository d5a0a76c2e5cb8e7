"""`make prove` (issue 41, docs/proof.md): Frama-C's Eva over the C runtime from the harnesses of
tests/proof/, once per configuration (a target's build: its limits, features and the C ABI its
compiler has), and the alarms Eva reports compared with the checked-in list tests/proof/alarms.txt.

Every alarm is a line of alarms.txt: configuration | file | function | kind | status | property |
classification ("real: ...", "imprecision: ..." or "unclassified"). An alarm Eva reports that the
list does not hold fails the run (a new alarm); so does a listed alarm Eva no longer reports (the
list must not go stale: delete the line, or run with --update to rewrite the list, keeping the
classifications of the lines that stay). Line numbers are not part of an alarm, so that an edit
elsewhere in the file does not change the list.

A run also fails when Frama-C fails, or when a harness's step loop was never reached (an analysis
that found every path dead would report no alarm and prove nothing).

    python tests/proof/prove.py [--config NAME ...] [--alarms FILE] [--update] [--work DIR]
"""

from __future__ import annotations

import argparse
import collections
import concurrent.futures
import csv
import os
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets.c import file_order
from swarmvm.targets.values import features, has_public_inputs, minimal_features

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
RUNTIME = ROOT / "runtime_c"
ALARMS = HERE / "alarms.txt"
# Eva's options, the same for every configuration: precision 1 (docs/proof.md, "Precision"), the
# states of a function split by its return value, so that `if (load(...) != SVM_OK)` keeps what
# an accepted image's layout is, no progress lines.
EVA = ["-eva", "-eva-precision", "1", "-eva-split-return", "auto", "-eva-no-show-progress"]
# What the harnesses print when their step loop is reached (Frama_C_show_each_<name>).
REACHED = "Frama_C_show_each_reached"
# The example's limits, as `gen` writes them into every target's build (10 events, 4 supervisors,
# 32 states: examples/energy_worker).
LIMITS = ["-DSVM_MAX_EVENTS=10", "-DSVM_MAX_SUPERVISORS=4", "-DSVM_MAX_STATES=32"]
OFF = "-DSVM_WITH_BINDINGS=0 -DSVM_WITH_FIRST=0".split()
# The Kilobot's builds (16-bit int) are analysed as avr-gcc compiles them, `__AVR__` defined, so
# that Eva sees their AVR branches (program-memory reads, the EEPROM medium, ATOMIC_BLOCK,
# avr-libc's CRC step), with avr_libc/'s stand-ins of the avr-libc headers they include.
AVR = ("-D__AVR__", "-I%s" % (HERE / "avr_libc"))
AVR_MACHDEP = "x86_16"      # the ATmega328P's ABI (16-bit int and pointers): an AVR build
# In every configuration: the contracts of the GCC builtins runtime_c/ calls (builtins.h).
BUILTINS = ("-include", str(HERE / "builtins.h"))
# What Frama-C says of a function it has neither code nor a contract for: Eva would go on with
# an assumption made from its prototype alone, so the run fails instead (add a contract).
UNKNOWN_FUNCTION = "Neither code nor specification for function"
# The minimal profile (swarmvm.h, SVM_TRUSTED_IMAGE): the image is the harness's proof_image, read
# as from flash, its masks the build's; the rest of its flags come from its model (model_build).
TRUSTED = ("-DSVM_TRUSTED_IMAGE=proof_image", "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1")
EXAMPLE = "examples/energy_worker/supervisor.yaml"
# What each profile of a model's build (Config.profile) compiles in: whether the image keeps its
# names (the streaming Kilobot matches a received image's events by name) and, from the targets'
# generator (swarmvm.targets.values), the features of the generated program: `minimal` the
# minimal profile (MINIMAL=1), `kilobot` the Kilobot's Makefile, `stream` its STREAM=1,
# `learned` its LEARNED=1; `sct` the features docs/robots/kilobot.md builds a published program's
# exact mode with (the binding table on).
PROFILES = ("minimal", "kilobot", "stream", "learned", "sct")


@dataclass(frozen=True)
class Config:
    """One Eva run: a harness, the runtime files it analyses with it, the -D flags, the machdep
    (the ABI: int and pointer sizes of the target's compiler)."""

    name: str
    harness: str
    sources: tuple[str, ...]
    defines: tuple[str, ...]
    machdep: str
    what: str = field(default="", compare=False)
    default: bool = True        # run by `make prove` (and `make test`) without --config
    # A harness that runs a generated image (proof_image.h, model_build): the model, and which of
    # the targets' builds of it sets its limits and features (PROFILES).
    model: str = ""
    profile: str = ""


CONFIGS = (     # the slowest first: two run at a time
    Config("stream", "harness_stream.c", ("swarmvm_stream.c", "swarmvm.c"),
           tuple(LIMITS + OFF + ["-DSVM_WITH_WEIGHTED=1", "-DSVM_WITH_LEARNED=1"]), AVR_MACHDEP,
           "the stream receiver as the streaming Kilobot builds it: chunks in any order, corrupted or not,"
           " each complete image loaded and stepped"),
    Config("learn", "harness_learn.c", ("swarmvm_learn.c", "swarmvm.c"),
           tuple(LIMITS + ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1", "-DSVM_WITH_NAMES=0"] + OFF
                 + ["-DSVM_WITH_WEIGHTED=0", "-DSVM_WITH_LEARNED=1"]), AVR_MACHDEP,
           "the learned policy (swarmvm_learn.c's svl_policy_*) as the Kilobot's SVM_LEARNED build compiles it:"
           " chooser, rewards, saved parameters loaded from unknown words; 16-bit int"),
    Config("logic-page", "harness_logic_page.c", ("swarmvm_logic_page.c", "swarmvm.c"),
           tuple(LIMITS + OFF + ["-DSVM_WITH_WEIGHTED=1", "-DSVM_WITH_LEARNED=1", "-DSVM_LOGIC_PAGE_SIZE=4096",
                                 "-DSVM_LOGIC_PAGE_ADDRESS=proof_page", "-include", str(HERE / "logic_page_stub.h")]),
           "x86_32", "the CapBot's control-logic page (4 KB of unknown bytes), as the capbot build compiles it"),
    Config("host", "harness_core.c", ("swarmvm.c",), tuple(LIMITS), "x86_64",
           "the `c` target's build: the model's limits, every feature on (swarmvm.h's defaults)"),
    Config("host-default", "harness_core.c", ("swarmvm.c",), (), "x86_64",
           "swarmvm.h's defaults (64 events: 8-byte masks; 65535 states: 2-byte states); no target builds"
           " it, and it takes as long as the others together: `--config host-default` (PROVE_CONFIGS)",
           default=False),
    Config("kilobot", "harness_core.c", ("swarmvm.c",),
           tuple(LIMITS + ["-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1", "-DSVM_WITH_NAMES=0"]
                 + OFF + ["-DSVM_WITH_WEIGHTED=1", "-DSVM_WITH_LEARNED=0"]), AVR_MACHDEP,
           "the Kilobot build (templates/kilobot/Makefile.j2): exact masks, no names, weighted on as"
           " for a model with probabilities; 16-bit int as on AVR"),
    Config("kilobot-stream", "harness_core.c", ("swarmvm.c",),
           tuple(LIMITS + OFF + ["-DSVM_WITH_WEIGHTED=1", "-DSVM_WITH_LEARNED=1"]), AVR_MACHDEP,
           "the streaming Kilobot build (STREAM=1, SVM_LEARNED=1): names on, masks not exact,"
           " learned and weighted on; 16-bit int"),
    Config("kilobot-minimal", "harness_trusted.c", ("swarmvm.c",), TRUSTED, AVR_MACHDEP,
           "the Kilobot's `make MINIMAL=1` (templates/kilobot/Makefile.j2): the example's image compiled in"
           " without names, run unchecked; 16-bit int", model=EXAMPLE, profile="minimal"),
    Config("capbot-minimal", "harness_trusted.c", ("swarmvm.c",), TRUSTED, "x86_32",
           "the CapBot's minimal profile (templates/capbot/qemu.mk.j2): the example's image compiled in,"
           " run unchecked; 32-bit int", model=EXAMPLE, profile="minimal"),
    Config("capbot", "harness_core.c", ("swarmvm.c",),
           tuple(LIMITS + OFF + ["-DSVM_WITH_WEIGHTED=1", "-DSVM_WITH_LEARNED=1"]), "x86_32",
           "the CapBot build (templates/capbot/CMakeLists.txt.j2, SVM_LEARNED=ON): names on, learned and"
           " weighted on; 32-bit int and pointers as on the Cortex-M4"),
    Config("sct", "harness_sct.c", ("swarmvm_sct.c", "swarmvm.c"), tuple(LIMITS), "x86_64",
           "the Nadzoru 2 C API (swarmvm_sct.c) in canonical mode as the `c` target builds it: any image,"
           " callbacks registered for any event number, any number of steps, resets and inits"),
    Config("sct-exact", "harness_sct.c", ("swarmvm_sct.c", "swarmvm.c"),
           ("-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1", "-DSVM_SCT_EXACT=1",
            "-DSVM_SCT_RANDOM=rand_soft"), AVR_MACHDEP,
           "the C API's exact mode as docs/robots/kilobot.md builds a published Kilobot program: the example's"
           " tables and file order, bindings on, draws from rand_soft; 16-bit int", model=EXAMPLE, profile="sct"),
    Config("store", "harness_store.c", ("swarmvm_store.c", "swarmvm.c"), (), AVR_MACHDEP,
           "the two-slot store of learned parameters (swarmvm_store.c): any medium bytes, block, slot size and"
           " base, saves and loads of any length, refused writes; 16-bit int"),
    Config("store-zephyr", "harness_store_zephyr.c", ("swarmvm_store_zephyr.c", "swarmvm_store.c", "swarmvm.c"),
           ("-I%s" % (ROOT / "firmware" / "capbot"),), "x86_32",
           "the CapBot's store on a Zephyr flash partition (swarmvm_store_zephyr.c): Zephyr's flash map calls"
           " answering as documented over any partition, write block and page size; 32-bit int"),
    Config("kilobot-glue", "harness_kilobot.c", ("swarmvm_kilobot.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"), AVR_MACHDEP,
           "the Kilobot glue (swarmvm_kilobot.c) of the generated program, `make`: unknown messages, ticks,"
           " uid, options and seeds around the example's image; 16-bit int", model=EXAMPLE, profile="kilobot"),
    Config("kilobot-glue-stream", "harness_kilobot.c", ("swarmvm_kilobot.c", "swarmvm_stream.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_STREAM=1"), AVR_MACHDEP,
           "the Kilobot glue of `make STREAM=1`: also image chunks of unknown bytes, matched, swapped in and"
           " stepped", model=EXAMPLE, profile="stream"),
    Config("kilobot-glue-learned", "harness_kilobot.c",
           ("swarmvm_kilobot.c", "swarmvm_learn.c", "swarmvm_learn_store.c", "swarmvm_store.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1", "-DSVM_LEARNED=1"), AVR_MACHDEP,
           "the Kilobot glue of `make LEARNED=1` on the learning example: the policy, rewards of any value and"
           " its EEPROM record (unknown bytes at any address)", model="examples/learning/supervisor.yaml",
           profile="learned"),
)
BY_NAME = {c.name: c for c in CONFIGS}

Alarm = tuple[str, str, str, str, str, str]     # configuration, file, function, kind, status, property


def frama_c() -> str | None:
    return shutil.which(os.environ.get("FRAMA_C", "frama-c"))


def command(config: Config, csv_path: Path, extra: tuple[str, ...] = ()) -> list[str]:
    avr = AVR if config.machdep == AVR_MACHDEP else ()
    defines = " ".join(("-I%s" % RUNTIME,) + BUILTINS + avr + config.defines + extra)
    files = [str(HERE / config.harness)] + [str(RUNTIME / s) for s in config.sources]
    return [frama_c() or "frama-c", "-machdep", config.machdep, "-cpp-extra-args=" + defines, *files,
            *EVA, "-then", "-report-csv", str(csv_path)]


@dataclass
class Run:
    config: Config
    alarms: list[Alarm]
    seconds: float
    log: Path
    error: str = ""


def parse_csv(config: str, path: Path) -> list[Alarm]:
    """The properties of the report that Eva did not prove: every alarm, and any precondition of a
    library function it could not establish."""
    alarms = []
    with path.open(newline="") as f:
        for row in csv.DictReader(f, delimiter="\t"):
            status = row["status"]
            if status.startswith(("Valid", "Considered valid", "Dead")):
                continue    # proved, assumed (the libc's own specifications), or unreachable
            if row["property kind"] in ("assigns clause", "from clause", "postcondition", "termination clause"):
                continue    # the libc's and builtins' own specifications, not alarms
            alarms.append((config, row["file"], row["function"], row["property kind"], status,
                           " ".join(row["property"].split())))
    return alarms


def model_build(config: Config, work: Path) -> tuple[str, ...]:
    """The generated build of `config.model` that a harness runs: its image (without names but in
    the stream profile) as proof_image, and in exact mode the supervisor file's order tables as
    the generated tables.c holds them (swarmvm.targets.c.file_order), written as proof_image.h into
    a folder of the configuration's own; and the flags of that build: that folder, the image's
    limits and the features of the configuration's profile (PROFILES), as the generated build has
    them."""
    if config.profile not in PROFILES:
        raise SystemExit(f"prove: configuration {config.name}: profile {config.profile!r} is not one of {PROFILES}")
    names = config.profile == "stream"
    compiled = compile_inputs([str(ROOT / config.model)], names=names)
    image, tables = compiled.image, compiled.tables
    folder = work / (config.name + ".include")
    folder.mkdir(parents=True, exist_ok=True)
    arrays: list[tuple[str, object]] = [("proof_image", image)]
    if config.profile == "sct":
        order = file_order(compiled)
        arrays += [("svm_sct_file_" + k, order["file_" + k]) for k in ("events", "states", "start")]
    (folder / "proof_image.h").write_text(
        "/* %s, generated by tests/proof/prove.py */\n" % config.model
        + "".join("const uint8_t %s[%d] = {%s};\n" % (n, len(b), ", ".join(map(str, b)))
                  for n, b in arrays if isinstance(b, bytes)))
    probabilistic = tables.probs is not None
    chosen = dict(features(probabilistic, names=names))
    if config.profile == "minimal":
        chosen.update(minimal_features(has_public_inputs(tables)))
    elif config.profile == "learned":
        chosen["LEARNED"] = 1
    elif config.profile == "sct":
        chosen = dict(BINDINGS=1, NAMES=0, FIRST=0, WEIGHTED=0, LEARNED=0)
    # the Makefile's LEARNED=1: room for states x controllable events
    theta = ["-DSVM_KILOBOT_THETA=%d" % (tables.num_states * bin(tables.controllable).count("1"))]
    return ("-I%s" % folder, "-DSVM_MAX_EVENTS=%d" % tables.num_events,
            "-DSVM_MAX_SUPERVISORS=%d" % tables.num_supervisors, "-DSVM_MAX_STATES=%d" % tables.num_states,
            *(theta if config.profile == "learned" else []), *("-DSVM_WITH_%s=%d" % kv for kv in chosen.items()))


def analyse(config: Config, work: Path, extra: tuple[str, ...] = ()) -> Run:
    """Eva on one configuration (`extra`: more -D flags, e.g. the planted defect of the tests)."""
    work.mkdir(parents=True, exist_ok=True)
    if config.model:
        extra = model_build(config, work) + extra
    csv_path, log = work / f"{config.name}.csv", work / f"{config.name}.log"
    start = time.monotonic()
    with log.open("w") as out:
        status = subprocess.run(command(config, csv_path, extra), stdout=out, stderr=subprocess.STDOUT,
                                cwd=ROOT).returncode
    seconds = time.monotonic() - start
    text = log.read_text(errors="replace")
    if status != 0 or not csv_path.exists():
        return Run(config, [], seconds, log, f"frama-c exited with {status} (log: {log})")
    unknown = sorted({line.split(UNKNOWN_FUNCTION, 1)[1].split(",")[0].strip()
                      for line in text.splitlines() if UNKNOWN_FUNCTION in line})
    if unknown:
        return Run(config, [], seconds, log, "no code or contract for %s: Eva would assume anything of it"
                   " (give it a contract in tests/proof/builtins.h or a stand-in; log: %s)" % (", ".join(unknown), log))
    if REACHED not in text:
        return Run(config, [], seconds, log, f"the harness's step loop was never reached (log: {log})")
    return Run(config, parse_csv(config.name, csv_path), seconds, log)


def read_list(path: Path) -> tuple[collections.Counter[Alarm], dict[Alarm, str]]:
    """The checked-in alarms (a multiset: one line per occurrence) and their classifications."""
    listed: collections.Counter[Alarm] = collections.Counter()
    why: dict[Alarm, str] = {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        head = line.split(" | ", 5)
        if len(head) != 6:
            raise SystemExit(f"{path}:{number}: not 'configuration | file | function | kind | status | ...'")
        prop, sep, classification = head[5].rpartition(" | ")
        if not sep or not classification.startswith(("real:", "imprecision:", "unclassified")):
            raise SystemExit(f"{path}:{number}: the last field must be 'real: ...', 'imprecision: ...' or"
                             " 'unclassified'")
        alarm = (head[0], head[1], head[2], head[3], head[4], prop)
        listed[alarm] += 1
        why[alarm] = classification
    return listed, why


def compare(found: collections.Counter[Alarm], listed: collections.Counter[Alarm]) -> list[str]:
    """The differences, one message each: alarms the list lacks, listed alarms no longer found."""
    messages = []
    for alarm, count in sorted((found - listed).items()):
        messages.append("new alarm (%d x): %s" % (count, " | ".join(alarm)))
    for alarm, count in sorted((listed - found).items()):
        messages.append("gone (%d x), delete its line from the list: %s" % (count, " | ".join(alarm)))
    return messages


def write_list(path: Path, found: collections.Counter[Alarm], why: dict[Alarm, str], keep: set[str]) -> None:
    """Rewrite the list: the configurations analysed from `found`, the others' lines as they were."""
    old = path.read_text().splitlines() if path.exists() else []
    header = [line for line in old if line.startswith("#")]
    others = [line for line in old if line and not line.startswith("#") and line.split(" | ", 1)[0] not in keep]
    lines = []
    for alarm in sorted(found.elements()):
        lines.append(" | ".join(alarm) + " | " + why.get(alarm, "unclassified"))
    path.write_text("\n".join(header + sorted(others + lines)) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--config", action="append", choices=sorted(BY_NAME), help="only these (repeatable)")
    parser.add_argument("--alarms", type=Path, default=ALARMS)
    parser.add_argument("--work", type=Path, default=ROOT / "build" / "proof")
    parser.add_argument("--update", action="store_true", help="rewrite the list from this run")
    parser.add_argument("--jobs", type=int, default=int(os.environ.get("PROVE_JOBS", "2")))
    parser.add_argument("-D", dest="defines", action="append", default=[], help="an extra -D for every harness")
    args = parser.parse_args(argv)
    if frama_c() is None:
        print("prove: frama-c not found (scripts/setup.sh installs frama-c-base)", file=sys.stderr)
        return 2
    configs = [BY_NAME[n] for n in args.config] if args.config else [c for c in CONFIGS if c.default]
    extra = tuple("-D" + d for d in args.defines)
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        runs = list(pool.map(lambda c: analyse(c, args.work, extra), configs))
    failed = [r for r in runs if r.error]
    found: collections.Counter[Alarm] = collections.Counter(a for r in runs for a in r.alarms)
    for r in runs:
        kinds = collections.Counter(a[3] for a in r.alarms)
        print("prove: %-15s %3d alarms in %5.1f s  %s" % (
            r.config.name, len(r.alarms), r.seconds,
            r.error or ", ".join("%s %d" % kv for kv in sorted(kinds.items()))))
    if failed:
        return 1
    listed, why = read_list(args.alarms) if args.alarms.exists() else (collections.Counter(), {})
    names = {c.name for c in configs}
    listed = collections.Counter({a: n for a, n in listed.items() if a[0] in names})
    if args.update:
        write_list(args.alarms, found, why, names)
        print(f"prove: wrote {args.alarms}")
        return 0
    messages = compare(found, listed)
    for message in messages:
        print("prove: " + message)
    print("prove: %d alarms, %s the list %s; %.0f s in all" % (
        sum(found.values()), "differing from" if messages else "as in", args.alarms, time.monotonic() - start))
    return 1 if messages else 0


if __name__ == "__main__":
    sys.exit(main())
