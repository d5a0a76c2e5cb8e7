"""Stream a new supervisor into a running Kilobot program, in simavr (docs/image-format.md,
"Streaming an image"). Shared by tests/kilobot/test_kilobot_swap.py and `make kilobot-swap-demo`.

The program is the generated Kilobot application of supervisor A built with SVM_STREAM, with a
test controller: each check follows a fixed pattern of kilo_ticks (``pattern``) and every step
prints one canonical trace line (docs/conformance.md), numbered from the last (re)start. The
emulator-only kilolib (firmware/kilobot/kilolib_emu.c) delivers a scripted list of messages,
compiled in from a generated ``kilo_emu_script.h``: the chunks of other images. ``reference``
gives what the Python reference VM prints for an image run from reset on the same pattern.

    python3 tests/kilobot_stream_demo.py OUTDIR      runs the demo and prints the trace change
"""

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from conformance import c_harness  # noqa: E402
from swarmvm.image import chunks  # noqa: E402
from swarmvm.pipeline import compile_inputs  # noqa: E402
from swarmvm.render import write_outputs  # noqa: E402
from swarmvm.naming import callback_stem  # noqa: E402
from swarmvm.runtime import python_vm  # noqa: E402
from checkout import FIRMWARE  # noqa: E402
from swarmvm.targets import generate  # noqa: E402

CORPUS = ROOT / "tests" / "corpus" / "openswarm"
SUPERVISOR_A = CORPUS / "hitl_leader.yaml"       # 10 events (6 public), 5 supervisors
SUPERVISOR_B = CORPUS / "network_leader.yaml"    # 8 of A's events, at other indices; 4 supervisors
NAME = "robot"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]

CONTROLLER = r"""/* Test controller (tests/kilobot_stream_demo.py): checks follow a fixed pattern of kilo_ticks,
 * each step prints one canonical trace line (docs/conformance.md), numbered from the last
 * (re)start; stream statuses print as "swap ok <length>", "stream refused <code>", ... */
#include "kilolib.h"
#include "kilolib_emu.h"
#include "%(name)s_tables.h"
#include "%(name)s_app.h"

static const char names[NUM_EVENTS][%(width)d] SVM_PROGMEM = {%(names)s};
static uint8_t fired[NUM_EVENTS];
static uint8_t nfired;
static uint16_t step;

/* Whether this program's event k occurs now (the same formula as the test's `pattern`). */
static unsigned char pattern(uint8_t k)
{
    uint16_t t = (uint16_t)kilo_ticks;
    return (unsigned char)((t + 3u * k) %% (k %% 4u + 2u) == 0u);
}

static void record(uint8_t k)
{
    if (nfired < NUM_EVENTS) {
        fired[nfired++] = k;
    }
}

static void print_name(uint8_t k)
{
    const char *p = names[k];
    char c;
    while ((c = (char)SVM_FLASH_BYTE(p++)) != '\0') {
        kilo_emu_put(c);
    }
}

void kilo_emu_after_loop(void)
{
    const svm_vm_t *vm = %(name)s_vm();
    uint8_t i;
    kilo_emu_print_uint(++step);
    kilo_emu_put(' ');
    if (nfired == 0) {
        kilo_emu_put('-');
    }
    for (i = 0; i < nfired; i++) {
        if (i != 0) {
            kilo_emu_put(',');
        }
        print_name(fired[i]);
    }
    for (i = 0; i < svm_num_supervisors(vm); i++) {
        kilo_emu_put(i != 0 ? ',' : ' ');
        kilo_emu_print_uint(svm_state(vm, i));
    }
    kilo_emu_put(' ');
    kilo_emu_print_uint(svm_violations(vm));
    kilo_emu_put('\n');
    nfired = 0;
}

void %(name)s_on_stream(uint8_t status, uint16_t value)
{
    switch (status) {
    case SVM_STREAM_RECEIVING:
        kilo_emu_print("stream receiving\n");
        return;
    case SVM_STREAM_COMPLETE:
        kilo_emu_print("swap ok ");
        step = 0;
        break;
    case SVM_STREAM_OUT_OF_SEQUENCE:
        kilo_emu_print("stream gap ");
        break;
    case SVM_STREAM_TOO_LARGE:
        kilo_emu_print("stream too large ");
        break;
    default:
        kilo_emu_print("stream refused ");
        break;
    }
    kilo_emu_print_uint(value);
    kilo_emu_put('\n');
}
%(callbacks)s"""


def pattern(tick, k):
    """Whether the program's event k (its index in A) occurs at kilo_ticks ``tick``."""
    return (tick + 3 * k) % (k % 4 + 2) == 0


def controller_source(compiled):
    events = compiled.model.events
    callbacks = []
    for k, e in enumerate(events):
        stem = callback_stem(e)
        callbacks.append("\nvoid %s_on_%s(void)\n{\n    record(EV_%s);\n}\n" % (NAME, stem, e))
        if not compiled.model.controllable[k] and not compiled.model.public[k]:
            callbacks.append("\nunsigned char %s_check_%s(void)\n{\n    return pattern(EV_%s);\n}\n" % (NAME, stem, e))
    return CONTROLLER % dict(name=NAME, width=max(len(e) for e in events) + 4,
                             names=", ".join('"EV_%s"' % e for e in events), callbacks="".join(callbacks))


def script_header(messages, loops):
    """kilo_emu_script.h: ``messages`` = [(loop, type, 9 data bytes)], sorted by loop."""
    rows = ["    {%du, 0x%02xu, {%s}}," % (loop, kind, ", ".join("0x%02x" % b for b in data))
            for loop, kind, data in messages]
    return "\n".join(["/* Scripted messages, generated by tests/kilobot_stream_demo.py. */",
                      "#define KILO_EMU_LOOPS %du" % loops,
                      "#define KILO_EMU_SCRIPT_COUNT %du" % len(messages),
                      "static const kilo_emu_rx_t kilo_emu_script[KILO_EMU_SCRIPT_COUNT] PROGMEM = {",
                      *rows, "};", ""])


class Program:
    """Supervisor A's Kilobot application with the test controller, built once in ``workdir``;
    ``run`` links it with a message script and runs it in simavr."""

    def __init__(self, workdir, supervisor=SUPERVISOR_A):
        self.workdir = Path(workdir)
        self.compiled = compile_inputs([str(supervisor)], name=NAME)
        self.workdir.mkdir(parents=True, exist_ok=True)
        write_outputs(self.workdir, generate(self.compiled, "kilobot"))
        (self.workdir / ("%s_controller.c" % NAME)).write_text(controller_source(self.compiled))
        app = (self.workdir / ("%s_app.h" % NAME)).read_text()
        self.chunk_type = int(re.search(r"#define SVM_MSG_IMAGE_CHUNK (0x[0-9a-fA-F]+)u", app).group(1), 16)
        # A's exact limits: a streamed image may only use A's events, and the corpus images
        # streamed here have no more supervisors or states than A.
        self.flags = [*c_harness.KILOBOT_FLAGS, *STRICT, *re.findall(
            r"-DSVM_MAX_[A-Z_]+=[0-9]+", (self.workdir / "Makefile").read_text()), "-DSVM_STREAM",
            "-I%s" % (FIRMWARE / "kilobot")]
        self.objects = []
        sources = ["%s_%s.c" % (NAME, part) for part in ("app", "controller", "tables")]
        for source in sources + ["swarmvm.c", "swarmvm_stream.c"]:
            obj = source[:-2] + ".o"
            self._cc("-c", source, "-o", obj)
            self.objects.append(obj)

    def _cc(self, *args):
        subprocess.run(["avr-gcc", *self.flags, *args], cwd=self.workdir, check=True, capture_output=True, text=True)

    def stream(self, image, first_loop, every=1):
        """Messages carrying ``image``: one chunk each ``every`` loops from ``first_loop``."""
        return [(first_loop + every * k, self.chunk_type, chunk) for k, chunk in enumerate(chunks(image))]

    def run(self, label, messages, loops):
        """simavr output lines of the program receiving ``messages`` over ``loops`` loops."""
        (self.workdir / "kilo_emu_script.h").write_text(script_header(sorted(messages, key=lambda m: m[0]), loops))
        elf = "%s_%s.elf" % (NAME, label)
        self._cc("-DKILO_EMU_SCRIPT", "-I.", *self.objects, str(FIRMWARE / "kilobot" / "kilolib_emu.c"), "-o", elf)
        return c_harness.run_avr(self.workdir / elf, timeout=60).splitlines()


def reference(compiled_a, image, first_tick, steps, received=()):
    """Trace lines of ``image`` run from reset by the Python VM, step j at kilo_ticks
    first_tick + j, its checks answered as the test controller does (events by name); a
    public event's check is true once, at the tick of each (tick, "EV_x") in ``received``."""
    vm_module = python_vm()
    vm = vm_module.VM(vm_module.Image.parse(image))
    model = compiled_a.model
    own = {n: k for k, n in enumerate(model.events)}
    inputs = [e for e in range(vm.image.num_events)
              if not (vm.image.controllable >> e) & 1 and not model.public[own[vm.image.event_name(e)[3:]]]]
    rows = [{e for e in inputs if pattern(first_tick + j, own[vm.image.event_name(e)[3:]])} for j in range(steps)]
    for tick, name in received:
        if 0 <= tick - first_tick < steps:
            rows[tick - first_tick].add(vm.image.event_index(name))
    return vm_module.replay(vm, rows)


def split(lines):
    """(trace lines before the swap, the "swap ..." line or None, trace lines after, stream
    lines) of a run's output."""
    before, after, swap, stream = [], [], None, []
    for line in lines:
        if line.startswith("swap "):
            swap = line
        elif line.startswith("stream "):
            stream.append(line)
        elif line[:1].isdigit():
            (after if swap else before).append(line)
    return before, swap, after, stream


def main(outdir):
    """Stream B with one corrupted chunk (refused: A keeps running), then B intact (swap)."""
    program = Program(outdir)
    image_b = compile_inputs([str(SUPERVISOR_B)]).image
    bad = program.stream(image_b, first_loop=4)
    bad[3] = (bad[3][0], bad[3][1], bad[3][2][:4] + bytes([bad[3][2][4] ^ 0x40]) + bad[3][2][5:])
    good = program.stream(image_b, first_loop=bad[-1][0] + 3)
    last, loops = good[-1][0], good[-1][0] + 12
    lines = [line for line in program.run("demo", bad + good, loops) if not line.startswith(("tx ", "end"))]
    before, swap, after, _ = split(lines)
    print("Kilobot (simavr atmega328p, emulator-only kilolib) running %s; %s (%d bytes) streamed twice as "
          "%d chunks (message type 0x%02x), one per loop: loops %d..%d with chunk 3 corrupted, then loops %d..%d intact"
          % (SUPERVISOR_A.stem, SUPERVISOR_B.stem, len(image_b), len(good), program.chunk_type, bad[0][0], bad[-1][0],
             good[0][0], last))
    shown = set(before[:3] + before[-3:] + after[:3] + after[-1:]) | {l for l in lines if not l[:1].isdigit()}
    gap = False
    for line in lines:
        if line in shown:
            print("    " + line)
            gap = False
        elif not gap:
            print("    ...")
            gap = True
    same_a = before == reference(program.compiled, program.compiled.image, 0, len(before))
    same_b = after == reference(program.compiled, image_b, len(before), len(after))
    print("%d steps of %s, then \"%s\" in loop %d (the last chunk's), then %d steps of %s from its initial states; "
          "both traces equal the Python reference VM's: %s"
          % (len(before), SUPERVISOR_A.stem, swap, last, len(after), SUPERVISOR_B.stem,
             "yes" if same_a and same_b else "NO"))
    return 0 if swap and same_a and same_b else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/kilobot/swap_demo"))
