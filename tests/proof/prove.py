"""`make prove` (issue 41, docs/proof.md): Frama-C's Eva over the C runtime from the harnesses of
tests/proof/, once per configuration (a target's build: its limits, features and the C ABI its
compiler has), and the alarms Eva reports compared with the checked-in list tests/proof/alarms.txt.

Every alarm is a line of alarms.txt: configuration | file | function | kind | status | property |
classification ("real: ...", "imprecision: ..." or "unclassified"). An alarm Eva reports that the
list does not hold fails the run (a new alarm); so does a listed alarm Eva no longer reports (the
list must not go stale: delete the line, or run with --update to rewrite the list, keeping the
classifications of the lines that stay). Line numbers are not part of an alarm, so that an edit
elsewhere in the file does not change the list.

WP proves what Eva cannot of the image checks (wp_units.py): check_indices' walk, which Eva takes
by its contract where the images are unknown, and the contracts of svm_validate and its helpers,
with CVC4 and Z3 through Why3, on `swarmvm.c` alone, once for every configuration whose build of
those functions is the same code. A property is proved when Eva or WP proves it; what neither
proves is an alarm.

A run also fails when Frama-C fails, when Why3 does not find both provers, or when a harness's
step loop was never reached (an analysis that found every path dead would report no alarm and
prove nothing).

    python tests/proof/prove.py [--config NAME ...] [--alarms FILE] [--update] [--work DIR]
"""

from __future__ import annotations

import argparse
import collections
import concurrent.futures
import csv
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets.c import file_order
from swarmvm.targets.values import features, has_public_inputs, minimal_features

if __package__:
    from .wp_units import CHECKS, UNIT_FUNCTIONS, UNITS, Unit, lemmas, present, unit_key, within
else:   # run as a script: its folder is on the path
    from wp_units import CHECKS, UNIT_FUNCTIONS, UNITS, Unit, lemmas, present, unit_key, within

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
RUNTIME = ROOT / "runtime_c"
ALARMS = HERE / "alarms.txt"
# Eva's options, the same for every configuration: precision 1 (docs/proof.md, "Precision"), the
# states of a function split by its return value, so that `if (load(...) != SVM_OK)` keeps what
# an accepted image's layout is, no progress lines.
EVA = ["-eva", "-eva-precision", "1", "-eva-split-return", "auto", "-eva-no-show-progress"]
# The report lists every property, also those no analysis tried (status Ignored): an annotation of
# runtime_c/ that nothing proved is an alarm, not a silence.
REPORT = ["-report-untried", "-report-csv"]
# WP's provers, each within 10 s a goal (none takes a second here; Qed, WP's simplifier, proves
# most goals itself), one goal at a time: two configurations run at once.
WP = ["-wp-prover", "cvc4,z3", "-wp-timeout", "10", "-wp-par", "1", "-wp-cache", "none"]
PROVERS = ("CVC4", "Z3")
# The libc's, the builtins' and the harnesses' own specifications: assumed, not alarms.
SPEC_KINDS = ("assigns clause", "from clause", "postcondition", "termination clause")
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
    # Whether the harness loads images of unknown bytes: Eva then takes check_indices by its
    # contract (its walk's relations between header fields are beyond intervals, and analysing it
    # multiplied Eva's states), and WP proves its body free of run-time errors (CHECKS).
    unknown_images: bool = True


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
           " without names, run unchecked; 16-bit int", model=EXAMPLE, profile="minimal", unknown_images=False),
    Config("capbot-minimal", "harness_trusted.c", ("swarmvm.c",), TRUSTED, "x86_32",
           "the CapBot's minimal profile (templates/capbot/qemu.mk.j2): the example's image compiled in,"
           " run unchecked; 32-bit int", model=EXAMPLE, profile="minimal", unknown_images=False),
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
           " tables and file order, bindings on, draws from rand_soft; 16-bit int", model=EXAMPLE, profile="sct", unknown_images=False),
    Config("store", "harness_store.c", ("swarmvm_store.c", "swarmvm.c"), (), AVR_MACHDEP,
           "the two-slot store of learned parameters (swarmvm_store.c): any medium bytes, block, slot size and"
           " base, saves and loads of any length, refused writes; 16-bit int", unknown_images=False),
    Config("store-zephyr", "harness_store_zephyr.c", ("swarmvm_store_zephyr.c", "swarmvm_store.c", "swarmvm.c"),
           ("-I%s" % (ROOT / "firmware" / "capbot"),), "x86_32",
           "the CapBot's store on a Zephyr flash partition (swarmvm_store_zephyr.c): Zephyr's flash map calls"
           " answering as documented over any partition, write block and page size; 32-bit int", unknown_images=False),
    Config("kilobot-glue", "harness_kilobot.c", ("swarmvm_kilobot.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1"), AVR_MACHDEP,
           "the Kilobot glue (swarmvm_kilobot.c) of the generated program, `make`: unknown messages, ticks,"
           " uid, options and seeds around the example's image; 16-bit int", model=EXAMPLE, profile="kilobot", unknown_images=False),
    Config("kilobot-glue-stream", "harness_kilobot.c", ("swarmvm_kilobot.c", "swarmvm_stream.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_STREAM=1"), AVR_MACHDEP,
           "the Kilobot glue of `make STREAM=1`: also image chunks of unknown bytes, matched, swapped in and"
           " stepped", model=EXAMPLE, profile="stream"),
    Config("kilobot-glue-learned", "harness_kilobot.c",
           ("swarmvm_kilobot.c", "swarmvm_learn.c", "swarmvm_learn_store.c", "swarmvm_store.c", "swarmvm.c"),
           ("-I%s" % HERE, "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_MASK_EXACT=1", "-DSVM_LEARNED=1"), AVR_MACHDEP,
           "the Kilobot glue of `make LEARNED=1` on the learning example: the policy, rewards of any value and"
           " its EEPROM record (unknown bytes at any address)", model="examples/learning/supervisor.yaml",
           profile="learned", unknown_images=False),
)
BY_NAME = {c.name: c for c in CONFIGS}

Alarm = tuple[str, str, str, str, str, str]     # configuration, file, function, kind, status, property
Row = dict[str, str]                            # a row of a -report-csv file
PROVED = ("Valid", "Considered valid")          # proved, or assumed (the libc's own specifications)


def frama_c() -> str | None:
    return shutil.which(os.environ.get("FRAMA_C", "frama-c"))


def frontend(config: Config, extra: tuple[str, ...]) -> list[str]:
    """Frama-C on `config`'s files, preprocessed with its flags and ABI."""
    avr = AVR if config.machdep == AVR_MACHDEP else ()
    defines = " ".join(("-I%s" % RUNTIME,) + BUILTINS + avr + config.defines + extra)
    files = [str(HERE / config.harness)] + [str(RUNTIME / s) for s in config.sources]
    return [frama_c() or "frama-c", "-machdep", config.machdep, "-cpp-extra-args=" + defines, *files]


def command(config: Config, csv_path: Path, extra: tuple[str, ...] = ()) -> list[str]:
    """Eva on `config`, its report into `csv_path`."""
    spec = ["-eva-use-spec", CHECKS.functions[0]] if config.unknown_images else []
    return [*frontend(config, extra), *EVA, *spec, "-then", *REPORT, str(csv_path)]


def wp_command(config: Config, unit: Unit, printed: str, csv_path: Path, out: Path,
               extra: tuple[str, ...]) -> list[str]:
    """WP on `unit` in `config`'s program (whose printing is `printed`: the harness's program, so
    that its report names what Eva's does as Eva's does), the report into `csv_path`."""
    every, assigns = present(unit, printed)
    line = [*frontend(config, extra), "-wp", *WP, "-wp-out", str(out)]
    # Every stage sets what it proves: an option set in one stage holds in the stages after it
    # ("-@lemma": every property of the functions; the lemmas have a stage of their own).
    selection = "-wp-prop=" + (unit.props or "-@lemma")
    stages = [["-wp-rte" if unit.rte else "-wp-no-rte", "-wp-fct", ",".join(every), selection]] if every else []
    stages += [["-wp-no-rte", "-wp-fct", ",".join(assigns), "-wp-prop=@assigns"]] if assigns else []
    stages += [["-wp-no-rte", "-wp-fct=", "-wp-prop=@lemma"]] if unit.lemmas else []
    for n, stage in enumerate(stages):
        line += (["-then"] if n else []) + stage
    return line + ["-then", *REPORT, str(csv_path)]


def why3_config(work: Path) -> tuple[dict[str, str], str]:
    """The environment that points WP's Why3 at a configuration of this run's own, in which Why3
    found the provers (`why3 config detect`), and what is missing, if anything."""
    if shutil.which("why3") is None:
        return {}, "why3 not found (scripts/setup.sh installs why3 cvc4 z3)"
    work.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, WHY3CONFIG=str(work / "why3.conf"))
    subprocess.run(["why3", "config", "detect"], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    text = (work / "why3.conf").read_text() if (work / "why3.conf").exists() else ""
    missing = [p for p in PROVERS if 'name = "%s"' % p not in text]
    return env, ("why3 found no %s (scripts/setup.sh installs why3 cvc4 z3)" % " or ".join(missing)
                 if missing else "")


@dataclass
class Run:
    config: Config
    alarms: list[Alarm]
    seconds: float
    log: Path
    error: str = ""


def reached_functions(config: Config, log: str) -> set[str]:
    """The functions Eva analysed (its final states of each, in the log), and those it took by
    their contracts, CHECKS, when it analysed their caller, validate."""
    reached = set(re.findall(r"Values at end of function (\w+)", log))
    return reached | set(CHECKS.functions) if config.unknown_images and "validate" in reached else reached


def read_report(path: Path) -> list[Row]:
    """The rows of a -report-csv file: tab-separated, unquoted, with a header line; a property of
    several lines (the libc's `complete behaviors`) goes on over the lines that follow its row."""
    rows: list[list[str]] = []
    with path.open(newline="") as f:
        for fields in csv.reader(f, delimiter="\t", quoting=csv.QUOTE_NONE):
            if rows and len(fields) < len(rows[0]):
                rows[-1][-1] += " " + "\t".join(fields)
            else:
                rows.append(fields)
    return [dict(zip(rows[0], fields)) for fields in rows[1:]] if rows else []


def row_keys(rows: list[Row]) -> list[tuple[str, ...]]:
    """Each row's identity in either report: its place and property, and which occurrence of them
    it is (a line may call a function twice with the same precondition)."""
    seen: collections.Counter[tuple[str, ...]] = collections.Counter()
    keys = []
    for row in rows:
        key = tuple(row[k] for k in ("directory", "file", "line", "function", "property kind")) + (
            " ".join(row["property"].split()),)
        seen[key] += 1
        keys.append(key + (str(seen[key]),))
    return keys


def unproved(config: Config, eva: list[Row], wp: list[Row], reached: set[str]) -> list[Alarm]:
    """The properties neither Eva nor WP proved: every alarm, every annotation of runtime_c/
    (contracts, loop invariants, assertions) not proved or never tried in the functions the
    configuration runs (`reached`), and any precondition of a library function they could not
    establish. Where Eva took check_indices by its contract, it reports its body, and what only
    that body calls, as dead: those rows are WP's to prove. WP proves a property "partially" when
    its proof rests on properties of the other run (a precondition at a call Eva analysed): those
    are rows of their own, proved or listed."""
    def eva_proves(row: Row) -> bool:
        if row["status"].startswith("Dead"):
            return not (config.unknown_images and row["function"] in CHECKS.functions)
        return row["status"].startswith(PROVED)
    by_eva = dict(zip(row_keys(eva), eva))
    by_wp = dict(zip(row_keys(wp), wp))
    keys = list(by_eva) + [k for k in by_wp if k not in by_eva]

    def alarm(key: tuple[str, ...]) -> Alarm | None:
        row, theirs = by_eva.get(key), by_wp.get(key)
        if (row is not None and eva_proves(row)) or (
                theirs is not None and theirs["status"].startswith(PROVED + ("Partially proven",))):
            return None
        if theirs is not None and (row is None or row["status"].startswith("Dead")):
            row = theirs
        assert row is not None
        status = row["status"]
        if Path(row["directory"]).name != RUNTIME.name and (row["property kind"] in SPEC_KINDS or status == "Ignored"):
            return None     # the libc's, builtins' and harnesses' own specifications, or ones never used
        if (status == "Ignored" or status.startswith("Dead")) and row["function"] not in reached:
            return None     # an annotation of a function this configuration never runs
        return (config.name, row["file"], row["function"], row["property kind"], status,
                " ".join(row["property"].split()))
    # A precondition of a unit's function (each is static and called only directly) is its calls'
    # rows ("precondition of f"), each proved by either run or an alarm of its own: its own row,
    # which has only one run's view of them, adds nothing.
    calls: dict[tuple[str, str], list[tuple[str, ...]]] = collections.defaultdict(list)
    for key in keys:
        if key[4].startswith("precondition of "):
            calls[(key[4].removeprefix("precondition of "), key[5])].append(key)
    found = {key: alarm(key) for key in keys}
    return [a for key, a in found.items() if a is not None and not (
        key[4] == "precondition" and key[3] in UNIT_FUNCTIONS and calls.get((key[3], key[5])))]


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


def analyse(config: Config, work: Path, extra: tuple[str, ...] = (), env: dict[str, str] | None = None) -> Run:
    """Eva, then WP on the image checks, on one configuration (`extra`: more -D flags, e.g. the
    planted defect of the tests; `env`: why3_config's, made here if not given)."""
    work.mkdir(parents=True, exist_ok=True)
    env = env if env is not None else why3_config(work)[0]
    if config.model:
        extra = model_build(config, work) + extra
    csv_path, log = work / f"{config.name}.csv", work / f"{config.name}.log"
    start = time.monotonic()
    with log.open("w") as out:
        status = subprocess.run(command(config, csv_path, extra), stdout=out, stderr=subprocess.STDOUT,
                                cwd=ROOT).returncode
    text = log.read_text(errors="replace")
    if status != 0 or not csv_path.exists():
        return Run(config, [], time.monotonic() - start, log, f"frama-c exited with {status} (log: {log})")
    unknown = sorted({line.split(UNKNOWN_FUNCTION, 1)[1].split(",")[0].strip()
                      for line in text.splitlines() if UNKNOWN_FUNCTION in line})
    if unknown:
        return Run(config, [], time.monotonic() - start, log, "no code or contract for %s: Eva would assume"
                   " anything of it (give it a contract in tests/proof/builtins.h or a stand-in; log: %s)"
                   % (", ".join(unknown), log))
    if REACHED not in text:
        return Run(config, [], time.monotonic() - start, log, f"the harness's step loop was never reached (log: {log})")
    reached = reached_functions(config, text)
    wp_rows: list[Row] = []
    printed = work / f"{config.name}.printed.c"
    units = [u for u in (within(u, reached) for u in UNITS) if u.functions or u.assigns_only]
    if units:
        with (work / f"{config.name}.print.log").open("w") as out:
            status = subprocess.run([*frontend(config, extra), "-print", "-ocode", str(printed)],
                                    stdout=out, stderr=subprocess.STDOUT, cwd=ROOT).returncode
        if status != 0 or not printed.exists():
            return Run(config, [], time.monotonic() - start, log,
                       f"frama-c -print exited with {status} (log: {out.name})")
    for unit in units:
        rows = prove_unit(config, unit, printed.read_text(), work, extra, env)
        if isinstance(rows, str):
            return Run(config, [], time.monotonic() - start, log, rows)
        wp_rows += rows
    return Run(config, unproved(config, read_report(csv_path), wp_rows, reached), time.monotonic() - start, log)


# The WP runs of this process, by work folder and unit_key: configurations whose build of a unit
# is the same code share one run (the first to need it makes it, the others wait for it).
_WP_RUNS: dict[tuple[Path, str], concurrent.futures.Future[list[Row] | str]] = {}
_WP_LOCK = threading.Lock()


def prove_unit(config: Config, unit: Unit, printed: str, work: Path, extra: tuple[str, ...],
               env: dict[str, str]) -> list[Row] | str:
    """WP's report of `unit` in `config`'s program (`printed`: Frama-C's printing of it), made by
    this call or by the one that first needed the same (unit_key), or why WP failed."""
    key = unit_key(unit, config.machdep, printed)
    with _WP_LOCK:
        run = _WP_RUNS.get((work, key))
        mine = run is None
        if run is None:
            run = _WP_RUNS[(work, key)] = concurrent.futures.Future()
    if not mine:
        return run.result()
    stem = work / f"wp-{unit.name}-{key}"
    result: list[Row] | str = f"WP on {unit.name} did not finish (log: {stem}.log)"
    try:        # whatever happens, the configurations waiting for this run get an answer
        result = run_wp(config, unit, printed, stem, extra, env)
    finally:
        run.set_result(result)
    return result


def run_wp(config: Config, unit: Unit, printed: str, stem: Path, extra: tuple[str, ...],
           env: dict[str, str]) -> list[Row] | str:
    """WP on `unit` in `config`'s program, its log, report and goals beside `stem`: the report's
    rows of the unit's functions (WP tries no other) and a row for each lemma, from the goals
    WP proved (the report has none for a lemma); or why WP failed."""
    csv_path, log = stem.with_suffix(".csv"), stem.with_suffix(".log")
    every, assigns = present(unit, printed)
    with log.open("w") as out:
        out.write("# %s, WP on %s (as built for %s)\n" % (unit.name, ", ".join(every + assigns), config.name))
        out.flush()
        status = subprocess.run(wp_command(config, unit, printed, csv_path, stem, extra), stdout=out,
                                stderr=subprocess.STDOUT, cwd=ROOT, env=env).returncode
    if status != 0 or not csv_path.exists():
        return f"frama-c's WP exited with {status} (log: {log})"
    proved = set(re.findall(r"Goal typed_lemma_(\w+) : Valid", log.read_text(errors="replace")))
    return [r for r in read_report(csv_path) if r["function"] in every + assigns] + [
        {"directory": RUNTIME.name, "file": "swarmvm.c", "line": "", "function": "", "property kind": "lemma",
         "status": "Valid" if name in proved else "Unknown", "property": name}
        for name in (lemmas(printed) if unit.lemmas else [])]


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
    env, missing = why3_config(args.work)
    if missing:
        print("prove: " + missing, file=sys.stderr)
        return 2
    configs = [BY_NAME[n] for n in args.config] if args.config else [c for c in CONFIGS if c.default]
    extra = tuple("-D" + d for d in args.defines)
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        runs = list(pool.map(lambda c: analyse(c, args.work, extra, env), configs))
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
