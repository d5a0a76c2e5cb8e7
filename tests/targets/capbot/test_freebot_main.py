"""FreeBot's published CapBot program, built unchanged, on its own VM and on swarmvm's (issue 35, 5).

The published program (../shared/reference/freebot-capbot-sct/: src/main.c, lib/sct/, CMakeLists.txt,
MIT) is read in place, never copied into the project. Its main.c is compiled unchanged against the
stand-in headers of tests/targets/capbot/freebot/include/ (Zephyr, Bluetooth, NUS, the FreeBot API:
none of them exists here) and linked with freebot/freebot_driver.c, which plays the phone: one
event script (one byte per step, see the driver's first comment) sends "e<x>,<y>,<angle>" messages
to the program's own NUS receive callback, between steps and in the middle of SCT_run_step's
polling, so that contradictory inputs (atWork and notAtWork both true in one step, ...) occur.
Each build prints a per-step log: every call the VM makes to the callbacks and checks main.c
registered, in order ("sct: check E = V", "sct: callback E": the link wraps main.c's
SCT_add_callback calls with tracing trampolines, -Wl,--wrap), the program's LOG_INF lines (its
callbacks' "EVENT:" and "ACTION:" among them) with the supervisors' states at each, and the states
at every step's end.

  (a) the published VM: lib/sct/src/sct_work_and_charge.c, -I lib/sct/inc, states from its
      sup_current_state[];
  (b) swarmvm in exact mode: the tables generated from that same .c file by `swarmvm gen` under the
      published header's name, runtime_c/swarmvm.c and swarmvm_sct.c with SVM_SCT_EXACT=1,
      states from SCT_state() (the file's numbering); built by following docs/robots/capbot.md's
      "Moving a published program over" (its commands run, its CMakeLists.txt change applied).

Both are built from the source lists of the (changed) CMakeLists.txt, on the host with gcc and
bare-metal for QEMU mps2-an386; the logs of (a) and (b) must be identical, step for step, and
QEMU's identical to the host's. rand(): main.c never seeds it; both VMs draw with the C library's
rand() from its default seed 1 (the same glibc on both sides on the host, newlib's in QEMU). For
the host-against-QEMU comparison the host build also runs with newlib's rand algorithm
(-DFREEBOT_NEWLIB_RAND, defined in the driver)."""

import random
import re
import shlex
import subprocess
from pathlib import Path

import pytest

from checkout import ROOT
from conformance import qemu_harness

FREEBOT = ROOT.parent / "shared" / "reference" / "freebot-capbot-sct"
STANDINS = Path(__file__).resolve().parent / "freebot"
INCLUDE = STANDINS / "include"
DRIVER = STANDINS / "freebot_driver.c"
DOC = ROOT / "docs" / "robots" / "capbot.md"
SECTION = "## Moving a published program over"
STEPS = 10_000
SEED = 35
SUPERVISORS = 4

pytestmark = pytest.mark.skipif(not (FREEBOT / "src" / "main.c").is_file(),
                                reason="needs the published FreeBot program in ../shared/reference/freebot-capbot-sct")

X_CHARGER, X_BETWEEN, X_WORK = 1, 2, 3


# ---- the event script ---------------------------------------------------------------------------

def event_script(steps=STEPS, seed=SEED):
    """One byte per step (freebot_driver.c): a message before the step (bits 0-1: x code), one
    during it (bits 2-3) after the program's (1 + bits 4-5)-th log call, the y code (bits 6-7).
    Quiet stretches (no message: the supervisors move through work and charge on their own) and
    stormy ones (x jumping between the charger and work, also in the middle of the polling)."""
    rng = random.Random(seed)
    script = []
    while len(script) < steps:
        stormy = rng.random() < 0.5
        for _ in range(rng.randint(5, 60)):
            if stormy:
                before = rng.choice([0, X_CHARGER, X_BETWEEN, X_WORK, X_WORK, X_CHARGER])
                during = rng.choice([0, X_CHARGER, X_WORK, X_BETWEEN]) if rng.random() < 0.6 else 0
            else:
                before = rng.choice([X_CHARGER, X_BETWEEN, X_WORK]) if rng.random() < 0.08 else 0
                during = 0
            script.append(before | during << 2 | rng.randrange(4) << 4 | rng.randrange(4) << 6)
    return bytes(script[:steps])


def write_script(folder, script):
    folder.mkdir(parents=True, exist_ok=True)
    rows = ",\n".join(", ".join("%d" % b for b in script[i:i + 24]) for i in range(0, len(script), 24))
    (folder / "freebot_script.h").write_text(
        "/* Written by tests/targets/capbot/test_freebot_main.py: the event script (freebot_driver.c). */\n"
        "#define FREEBOT_STEPS %d\nstatic const unsigned char freebot_script[FREEBOT_STEPS] = {\n%s\n};\n"
        % (len(script), rows))
    return folder


# ---- CMakeLists.txt: the sources a build compiles ------------------------------------------------

def cmake_build(cmake_text, app):
    """(sources, include folders, definitions) of the `app` target in a Zephyr CMakeLists.txt:
    its uncommented target_sources, include_directories and target_compile_definitions, the FreeBot
    library's (lib/freebot/, not in the published folder: freebot.h is a stand-in) left out, and of
    `if(DEFINED FB_DUMMY_API) ... else()` the else branch (the build without -DFB_DUMMY_API)."""
    sources, includes, defines = [], [], []
    skipping = False
    for raw in cmake_text.splitlines():
        line = raw.split("#", 1)[0].strip()
        if line.startswith("if(DEFINED FB_DUMMY_API"):
            skipping = True
        elif line.startswith("else(") or line.startswith("endif("):
            skipping = False
        if skipping or not line:
            continue
        call = re.match(r"(\w+)\((.*)\)$", line)
        if not call:
            continue
        verb, args = call.group(1), shlex.split(call.group(2))
        if verb == "target_sources" and args[:2] == ["app", "PRIVATE"]:
            sources += [a for a in args[2:] if not a.startswith("lib/freebot/")]
        elif verb == "include_directories":
            includes += [a for a in args if not a.startswith("lib/freebot/")]
        elif verb == "target_compile_definitions" and args[:2] == ["app", "PRIVATE"]:
            defines += args[2:]
    return [app / s for s in sources], [app / i for i in includes], defines


def doc_section():
    text = DOC.read_text()
    assert SECTION in text, "docs/robots/capbot.md has no %r" % SECTION
    section = text.split(SECTION, 1)[1]
    return section.split("\n## ", 1)[0]


def doc_blocks(kind):
    return [m.group(1) for m in re.finditer(r"^```%s\n(.*?)^```" % kind, doc_section(), re.M | re.S)]


def apply_cmake_change(cmake_text, diff):
    """The doc's ```diff of CMakeLists.txt applied as one hunk: its context and '-' lines must be
    consecutive lines of the published file; they become its context and '+' lines."""
    lines = cmake_text.splitlines()
    hunk = [d for d in diff.splitlines() if d[:1] in (" ", "-", "+")]
    old = [d[1:] for d in hunk if d[0] in " -"]
    new = [d[1:] for d in hunk if d[0] in " +"]
    at = [i for i in range(len(lines) - len(old) + 1) if lines[i:i + len(old)] == old]
    assert len(at) == 1, "the doc's CMakeLists.txt change does not apply to the published file:\n" + "\n".join(old)
    return "\n".join(lines[:at[0]] + new + lines[at[0] + len(old):]) + "\n"


def published_folder(tmp):
    """A FreeBot user's checkout: the published files, linked in place (read-only), and lib/ a
    real folder so that generated files land in the scratch folder, never in the reference."""
    app = tmp / "freebot-capbot-sct"
    (app / "lib").mkdir(parents=True)
    for name in ("src", "CMakeLists.txt", "prj.conf", "LICENSE"):
        (app / name).symlink_to(FREEBOT / name)
    (app / "lib" / "sct").symlink_to(FREEBOT / "lib" / "sct")
    return app


def migrated_folder(tmp):
    """The published folder moved over to swarmvm by the doc's steps: its ```sh commands run in
    the folder above the checkout (lines starting with `west` or `cd` left out: no Zephyr here),
    then its CMakeLists.txt change applied. (app, changed CMakeLists.txt text)."""
    app = published_folder(tmp)
    commands = [c for block in doc_blocks("sh") for c in block.splitlines()
                if c.strip() and not c.lstrip().startswith(("#", "west", "cd "))]
    assert any(c.startswith("swarmvm gen") for c in commands), "the doc's steps generate nothing"
    run = subprocess.run(["bash", "-c", "set -e -o pipefail\n" + "\n".join(commands)], cwd=tmp,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, "\n".join(commands) + "\n" + run.stdout[-2000:] + run.stderr[-2000:]
    (diff,) = doc_blocks("diff")
    return app, apply_cmake_change((app / "CMakeLists.txt").read_text(), diff)


# ---- builds ---------------------------------------------------------------------------------------

PROGRAM_FLAGS = ["-std=c99", "-imacros", str(INCLUDE / "autoconf.h"), "-I", str(INCLUDE),
                 "-I", str(qemu_harness.CAPBOT)]          # logging/log.h: firmware/capbot's stand-in
DRIVER_WARNINGS = ["-Wall", "-Wextra", "-Werror", "-pedantic"]
M4_FLAGS = (qemu_harness.CAPBOT / "m4.flags").read_text().split()
M4_CPU = [f for f in M4_FLAGS if f.startswith(("-mcpu", "-mthumb", "-mfloat-abi", "-mfpu"))]
M4_COMPILE = M4_CPU + ["-Os", "-ffunction-sections", "-fdata-sections"]
TRACE_CALLBACKS = "-Wl,--wrap=SCT_add_callback"     # main.c's registrations traced (freebot_driver.c)
M4_LINK = M4_CPU + [f for f in M4_FLAGS if f.startswith(("--specs", "-nostartfiles", "-Wl,"))]


def build(folder, sources, includes, defines, swarmvm, target="host", newlib_rand=False):
    """Compile the program's sources (its own flags: main.c is not ours, its warnings are not
    errors) and the driver (-Wall -Wextra -Werror -pedantic), link; the program or ELF path."""
    folder.mkdir(parents=True, exist_ok=True)
    cc, extra, link = (["gcc"], ["-O2"], []) if target == "host" else \
        (["arm-none-eabi-gcc"], M4_COMPILE, M4_LINK + ["-T", str(qemu_harness.LINKER_SCRIPT)])
    flags = PROGRAM_FLAGS + extra + ["-D%s" % d for d in defines] + ["-I%s" % i for i in includes]
    driver_defines = ["-DFREEBOT_SUPERVISORS=%d" % SUPERVISORS, "-DFREEBOT_TRACE_CALLBACKS"] + \
        (["-DFREEBOT_SWARMVM"] if swarmvm else []) + (["-DFREEBOT_NEWLIB_RAND"] if newlib_rand else [])
    objects = []
    units = [(s, flags) for s in sources] + [(DRIVER, flags + DRIVER_WARNINGS + driver_defines + ["-I", str(folder)])]
    if target != "host":
        units.append((qemu_harness.STARTUP, flags + DRIVER_WARNINGS))
    for source, unit_flags in units:
        obj = folder / (Path(source).stem + ".o")
        compile_or_fail(cc + unit_flags + ["-c", str(source), "-o", str(obj)])
        objects.append(str(obj))
    program = folder / ("freebot" if target == "host" else "freebot.elf")
    compile_or_fail(cc + link + objects + [TRACE_CALLBACKS, "-o", str(program)])
    return program


def compile_or_fail(command):
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 0, " ".join(command) + "\n" + done.stderr[-3000:]


def run_host(program):
    done = subprocess.run([str(program)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def run_qemu(elf):
    status, stdout, stderr = qemu_harness.run(elf, timeout=300)
    assert status == 0, stderr
    return stdout.splitlines()


def published_build(tmp, script, target="host", newlib_rand=False):
    app = published_folder(tmp)
    sources, includes, defines = cmake_build((app / "CMakeLists.txt").read_text(), app)
    assert [s.name for s in sources] == ["sct_work_and_charge.c", "main.c"]
    return build(write_script(tmp / "build", script), sources, includes, defines, swarmvm=False,
                 target=target, newlib_rand=newlib_rand)


def swarmvm_build(tmp, script, target="host", newlib_rand=False, exact=True):
    """(b); exact=False: the same, SVM_SCT_EXACT=0 (swarmvm's canonical mode) instead of the doc's 1."""
    app, cmake = migrated_folder(tmp)
    sources, includes, defines = cmake_build(cmake, app)
    assert "SVM_SCT_EXACT=1" in defines
    if not exact:
        defines = ["SVM_SCT_EXACT=0" if d == "SVM_SCT_EXACT=1" else d for d in defines]
    assert "sct_work_and_charge.c" not in [s.name for s in sources], "the published VM is still built"
    assert (app / "src" / "main.c").resolve() == (FREEBOT / "src" / "main.c").resolve()
    return build(write_script(tmp / "build", script), sources, includes, defines, swarmvm=True,
                 target=target, newlib_rand=newlib_rand)


# ---- what a log shows -----------------------------------------------------------------------------

STEP_END = re.compile(r"^(\d{5}) end ((?:\d+ ?)+)$")


def steps_of(log):
    """{step: [lines]} of a log."""
    steps = {}
    for line in log:
        steps.setdefault(int(line[:5]), []).append(line[6:])
    return steps


def first_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return "line %d: %r != %r" % (i + 1, x, y)
    return "lengths %d != %d" % (len(a), len(b))


def assert_rich(log, steps=STEPS):
    """The run is the whole script and exercises what the comparison is for: every step ends
    with its states; contradictory inputs in one step; every action; many joint states."""
    per_step = steps_of(log)
    assert sorted(per_step) == list(range(steps + 1))
    ends = [line for line in log if STEP_END.match(line)]
    assert len(ends) == steps + 1
    contradictory = sum(1 for lines in per_step.values()
                        if {"<inf> EVENT: atWork", "<inf> EVENT: notAtWork"} <= {ln.split(" [")[0] for ln in lines}
                        or {"<inf> EVENT: atCharger", "<inf> EVENT: notAtCharger"} <= {ln.split(" [")[0] for ln in lines})
    assert contradictory > 200, contradictory
    actions = {ln[6:].split(" [")[0] for ln in log if "ACTION:" in ln}
    assert actions == {"<inf> ACTION: %s" % a for a in ("moveToWork", "work", "moveToCharge", "charge")}
    assert len({STEP_END.match(e).group(2) for e in ends}) >= 10


# ---- the tests ------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def script():
    return event_script()


@pytest.fixture(scope="module")
def published_host_log(tmp_path_factory, script):
    return run_host(published_build(tmp_path_factory.mktemp("published"), script))


def test_the_published_main_compiles_unchanged_with_either_security_setting(tmp_path):
    """main.c against the stand-ins, also with CONFIG_BT_NUS_SECURITY_ENABLED (the branch the
    published prj.conf leaves out), with no error."""
    for defines in ([], ["-DCONFIG_BT_NUS_SECURITY_ENABLED=1"]):
        subprocess.run(["gcc", *PROGRAM_FLAGS, *defines, "-I", str(FREEBOT / "lib" / "sct" / "inc"), "-c",
                        str(FREEBOT / "src" / "main.c"), "-o", str(tmp_path / "main.o")], check=True)


def test_the_event_script_is_deterministic_and_long():
    assert event_script() == event_script() and len(event_script()) >= 10_000
    assert event_script(seed=1) != event_script()


def test_the_published_vm_runs_the_whole_script_on_the_host(published_host_log):
    """(a): main.c with the published lib/sct/src/sct_work_and_charge.c, 10,000 steps."""
    assert_rich(published_host_log)
    assert "00000 <inf> Connected C0:FF:EE:00:00:33 (random) [0 0 0 0]" in published_host_log
    assert "00001 nus send: 2a 33" in published_host_log        # the program's ID message


def test_the_published_vm_polls_in_file_order_and_draws_every_step(published_host_log):
    """The published step as the traced calls show it: in every step of the loop, the checks of
    all four uncontrollable events called once each, in the file's event order (EV_atWork 0,
    EV_atCharger 2, EV_notAtCharger 3, EV_notAtWork 6), before any callback; and a controllable
    event drawn and called back also in steps with no new input."""
    text = (FREEBOT / "lib" / "sct" / "inc" / "sct_work_and_charge.h").read_text()
    numbers = {name: int(n) for name, n in re.findall(r"#define EV_(\w+) (\d+)", text)}
    polled = sorted(numbers[e] for e in ("atWork", "notAtWork", "atCharger", "notAtCharger"))
    assert polled == [0, 2, 3, 6]
    controllable = {numbers[e] for e in ("moveToWork", "work", "moveToCharge", "charge")}
    quiet_actions = 0
    for step, lines in steps_of(published_host_log).items():
        calls = [ln.split(" [")[0] for ln in lines if ln.startswith("sct: ")]
        checks = [int(c.split()[2]) for c in calls if c.startswith("sct: check")]
        assert checks == (polled if step > 0 else []), (step, calls)
        callbacks = [int(c.split()[2]) for c in calls if c.startswith("sct: callback")]
        assert all(c.startswith("sct: check") for c in calls[:len(checks)]), (step, calls)
        assert len(callbacks) <= 1 and set(callbacks) <= controllable, (step, calls)   # only actions have callbacks
        if callbacks and not any(ln.startswith("phone:") for ln in lines):     # no new input
            quiet_actions += 1
    assert quiet_actions > 100, quiet_actions


REACHABLE_C = r"""
#include <stdio.h>
#include "sct_work_and_charge.h"
extern unsigned long int sup_current_state[];
extern const unsigned char ev_controllable[];
unsigned char get_active_controllable_events(unsigned char *events);
void make_transition(unsigned char event);
static void set(int joint) { int i; for (i = 0; i < NUM_SUPERVISORS; ++i) sup_current_state[i] = joint >> 3 * i & 7; }
int main(void)
{
    static unsigned char seen[1 << 3 * NUM_SUPERVISORS];
    static int queue[1 << 3 * NUM_SUPERVISORS];
    int head = 0, tail = 0, most = 0;
    seen[0] = 1;
    queue[tail++] = 0;
    while (head < tail) {
        int joint = queue[head++], e, i, n;
        unsigned char enabled[NUM_EVENTS];
        set(joint);
        n = get_active_controllable_events(enabled);
        most = n > most ? n : most;
        for (e = 0; e < NUM_EVENTS; ++e) {
            int next = 0;
            if (ev_controllable[e] && !enabled[e]) continue;
            set(joint);
            make_transition((unsigned char)e);
            for (i = 0; i < NUM_SUPERVISORS; ++i) next |= (int)sup_current_state[i] << 3 * i;
            if (!seen[next]) { seen[next] = 1; queue[tail++] = next; }
        }
    }
    printf("%d %d\n", tail, most);
    return 0;
}
"""


def test_in_this_model_the_draw_never_has_a_choice(tmp_path):
    """Why the logs cannot tell two draw orders apart: through the published VM's own functions,
    every joint state reachable by the events it applies (uncontrollable ones anywhere, enabled
    controllable ones) has at most one enabled controllable event, so rand() % n is 0."""
    (tmp_path / "reachable.c").write_text(REACHABLE_C)
    subprocess.run(["gcc", "-I", str(FREEBOT / "lib" / "sct" / "inc"), str(tmp_path / "reachable.c"),
                    str(FREEBOT / "lib" / "sct" / "src" / "sct_work_and_charge.c"), "-o", str(tmp_path / "reachable")],
                   check=True)
    reachable, most = map(int, subprocess.run([str(tmp_path / "reachable")], check=True, capture_output=True,
                                              text=True).stdout.split())
    assert (reachable, most) == (25, 1)


def test_swarmvm_in_exact_mode_logs_what_the_published_vm_logs(tmp_path, script, published_host_log):
    """(b): the same main.c, moved over by the doc's steps: swarmvm's generated tables and runtime
    in exact mode; per-step log identical to (a)'s."""
    log = run_host(swarmvm_build(tmp_path, script))
    assert log == published_host_log, first_difference(log, published_host_log)


def test_the_comparison_tells_canonical_mode_from_exact_mode(tmp_path, script, published_host_log):
    """The same build in swarmvm's canonical mode (level inputs, name order): with the states left
    out (their numbering differs), its callbacks still differ from the published VM's in many
    steps, so the identical logs above are the exact mode's doing, not the script's weakness."""
    def calls(log):
        per_step = steps_of([re.sub(r" \[[\d ]*\]$", "", ln) for ln in log if not STEP_END.match(ln)])
        return per_step
    canonical, published = calls(run_host(swarmvm_build(tmp_path, script, exact=False))), calls(published_host_log)
    differing = sum(1 for step in published if published[step] != canonical.get(step))
    assert differing > 500, differing


@pytest.mark.emulator
@pytest.mark.slow
def test_in_qemu_both_vms_log_what_the_host_logs(tmp_path, script):
    """(a) and (b) bare-metal on the Cortex-M4F (QEMU mps2-an386, newlib's rand from seed 1):
    logs identical to each other and to the host's build with newlib's rand algorithm."""
    host = run_host(published_build(tmp_path / "host", script, newlib_rand=True))
    assert_rich(host)
    published = run_qemu(published_build(tmp_path / "m4a", script, target="m4"))
    assert published == host, first_difference(published, host)
    ours = run_qemu(swarmvm_build(tmp_path / "m4b", script, target="m4"))
    assert ours == published, first_difference(ours, published)


def test_the_doc_shows_the_changed_cmake_lines_and_exact_mode():
    (diff,) = doc_blocks("diff")
    assert "-target_sources(app PRIVATE lib/sct/src/sct_work_and_charge.c)" in diff.splitlines()
    assert any(line.startswith("+") and "SVM_SCT_EXACT=1" in line for line in diff.splitlines())
