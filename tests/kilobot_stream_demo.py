"""Stream a new supervisor into a running Kilobot program, in simavr (docs/image-format.md,
"Streaming an image"). Shared by tests/targets/kilobot/test_kilobot_swap.py and `make kilobot-swap-demo`.

The program is the generated Kilobot application of supervisor A built with SVM_STREAM and
linked with the real kilolib, with a test controller: each check follows a fixed pattern of the
step count (``pattern``) and every step prints, over kilolib's debug output (USART0), one
canonical trace line (docs/conformance.md), numbered from the last (re)start; the first step
also prints "first <kilo_ticks>". It runs on the simavr Kilobot board (firmware/kilobot/board.py),
which starts it with the overhead controller's RUN message and sends it, over IR, the chunks of
other images at given kilolib ticks. The VM steps once per tick, so a message that arrived in
tick T counts at the step of tick T + 1 (``Program.step_of``). ``reference`` gives what the
Python reference VM prints for an image run from reset on the same pattern.

    python3 tests/kilobot_stream_demo.py OUTDIR      runs the demo and prints the trace change
"""

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

sys.path.insert(0, str(ROOT / "firmware" / "kilobot"))

import board  # noqa: E402
from conformance import c_harness  # noqa: E402
from kilolib_build import kilolib_dir  # noqa: E402
from swarmvm.compiler.image import chunks  # noqa: E402
from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm.boundary.output import write_outputs  # noqa: E402
from swarmvm.compiler.naming import callback_stem  # noqa: E402
from swarmvm.compiler.runtime_files import python_vm, reference_vm  # noqa: E402
from swarmvm.targets import generate  # noqa: E402
from swarmvm.targets.kilobot import uid_seed  # noqa: E402

CORPUS = ROOT / "tests" / "corpus" / "openswarm"
SUPERVISOR_A = CORPUS / "hitl_leader.yaml"       # 10 events (6 public), 5 supervisors
SUPERVISOR_B = CORPUS / "network_leader.yaml"    # 8 of A's events, at other indices; 4 supervisors
NAME = "robot"
# A kilolib tick by which the program runs: kilolib, idle, blinks its LED with 200 ms delays, so
# it takes the RUN message (sent at tick 1) up to 7 ticks later; messages before that are lost.
RUNNING = 12
# The board's EEPROM is erased unless a test gives one: kilo_uid 0xFFFF, whose seed the VM draws
# from (swarmvm_kilobot.h, SVM_KILOBOT_UID_SEED).
ERASED_UID = 0xFFFF
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]

CONTROLLER = r"""/* Test controller (tests/kilobot_stream_demo.py): checks follow a fixed pattern of the step
 * count, each step prints one canonical trace line (docs/conformance.md), numbered from the
 * last (re)start; stream statuses print as "swap ok <length>", "stream refused <code>", ...
 * Output: kilolib's debug.h (USART0). */
#define DEBUG
#include "kilolib.h"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"   /* kilolib's debug.h, under -Wextra */
#include "debug.h"
#pragma GCC diagnostic pop
#include "%(name)s_tables.h"
#include "%(name)s_app.h"

static const char names[NUM_EVENTS][%(width)d] SVM_PROGMEM = {%(names)s};
static uint8_t fired[NUM_EVENTS];
static uint8_t nfired;
static uint16_t step, steps;

static void put_char(char c)
{
    static uint8_t ready;
    if (!ready) {
        debug_init();
        ready = 1;
    }
    putchar(c);
}

static void put_text(const char *s)
{
    while (*s != '\0') {
        put_char(*s++);
    }
}

static void put_uint(uint32_t value)
{
    char digits[10];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + value %% 10u);
        value /= 10u;
    } while (value != 0u);
    while (n != 0u) {
        put_char(digits[--n]);
    }
}

/* Whether this program's event k occurs now (the same formula as the test's `pattern`). */
static unsigned char pattern(uint8_t k)
{
    return (unsigned char)((steps + 3u * k) %% (k %% 4u + 2u) == 0u);
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
        put_char(c);
    }
}

void svm_kilobot_after_step(void)
{
    const svm_vm_t *vm = %(name)s_vm();
    uint8_t i;
    if (steps++ == 0u) {
        put_text("first ");
        put_uint(kilo_ticks);
        put_char('\n');
    }
    put_uint(++step);
    put_char(' ');
    if (nfired == 0) {
        put_char('-');
    }
    for (i = 0; i < nfired; i++) {
        if (i != 0) {
            put_char(',');
        }
        print_name(fired[i]);
    }
    for (i = 0; i < svm_num_supervisors(vm); i++) {
        put_char(i != 0 ? ',' : ' ');
        put_uint(svm_state(vm, i));
    }
    put_char(' ');
    put_uint(svm_violations(vm));
    put_char('\n');
    nfired = 0;
}

void %(name)s_stream_status(uint8_t status, uint16_t value)
{
    switch (status) {
    case SVM_STREAM_RECEIVING:
        put_text("stream receiving\n");
        return;
    case SVM_STREAM_COMPLETE:
        put_text("swap ok ");
        step = 0;
        break;
    case SVM_STREAM_OUT_OF_SEQUENCE:
        put_text("stream gap ");
        break;
    case SVM_STREAM_TOO_LARGE:
        put_text("stream too large ");
        break;
    default:
        put_text("stream refused ");
        break;
    }
    put_uint(value);
    put_char('\n');
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


class Program:
    """Supervisor A's Kilobot application with the test controller, built once in ``workdir``
    against the real kilolib; ``run`` runs it on the simavr Kilobot board."""

    def __init__(self, workdir, supervisor=SUPERVISOR_A, defines=()):
        self.workdir = Path(workdir)
        self.compiled = compile_inputs([str(supervisor)], name=NAME)
        self.workdir.mkdir(parents=True, exist_ok=True)
        write_outputs(self.workdir, generate(self.compiled, "kilobot"))
        (self.workdir / ("%s_controller.c" % NAME)).write_text(controller_source(self.compiled))
        runtime = (self.workdir / "swarmvm_kilobot.h").read_text()
        self.chunk_type = int(re.search(r"#define SVM_MSG_IMAGE_CHUNK (0x[0-9a-fA-F]+)u", runtime).group(1), 16)
        # A's exact limits: a streamed image may only use A's events, and the corpus images
        # streamed here have no more supervisors or states than A.
        kilolib = kilolib_dir()
        limits = re.findall(r"-DSVM_MAX_[A-Z_]+=[0-9]+", (self.workdir / "Makefile").read_text())
        # The generated program's own files (main, app, controller, tables, dispatch).
        sources = sorted(path.name for path in self.workdir.glob("%s_*.c" % NAME))
        self.elf = self.workdir / ("%s.elf" % NAME)
        subprocess.run(["avr-gcc", *c_harness.KILOBOT_FLAGS, *STRICT, *limits, "-DSVM_STREAM", *defines, "-I%s" % kilolib,
                        *sources, "swarmvm.c", "swarmvm_stream.c", "swarmvm_kilobot.c",
                        str(kilolib / "build" / "kilolib.a"), "-o", self.elf.name],
                       cwd=self.workdir, check=True, capture_output=True, text=True)

    def stream(self, image, first_tick, every=1):
        """Messages carrying ``image``: one chunk each ``every`` ticks from ``first_tick``."""
        return [(first_tick + every * k, self.chunk_type, chunk) for k, chunk in enumerate(chunks(image))]

    def run(self, messages, ticks):
        """The board's Run of the program receiving ``messages`` [(tick, type, data)] until
        kilo_ticks reaches ``ticks``."""
        return board.run(self.elf, ticks, messages)

    @staticmethod
    def step_of(lines, tick):
        """The step (counted from 0 over the whole run) at which a message that arrived in
        kilolib tick ``tick`` counts: the next tick's."""
        first = next(int(line.split()[1]) for line in lines if line.startswith("first "))
        return tick + 1 - first


def reference(compiled_a, image, first_tick, steps, received=(), uid=ERASED_UID, **options):
    """Trace lines of ``image`` run from reset by the reference VM with the seed of the robot
    ``uid`` (and ``options``: inputs, control, policy, seed), step j at kilo_ticks first_tick + j,
    its checks answered as the test controller does (events by name); a public event's check is
    true once, at the tick of each (tick, "EV_x") in ``received``."""
    vm = reference_vm().ReferenceVM(image, **{"seed": uid_seed(uid), **options})
    model = compiled_a.model
    own = {n: k for k, n in enumerate(model.events)}
    inputs = [e for e in range(vm.image.num_events)
              if not (vm.image.controllable >> e) & 1 and not model.public[own[vm.image.event_name(e)[3:]]]]
    rows = [{e for e in inputs if pattern(first_tick + j, own[vm.image.event_name(e)[3:]])} for j in range(steps)]
    for tick, name in received:
        if 0 <= tick - first_tick < steps:
            rows[tick - first_tick].add(vm.image.event_index(name))
    return python_vm().replay(vm, rows)


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
    bad = program.stream(image_b, first_tick=RUNNING)
    bad[3] = (bad[3][0], bad[3][1], bad[3][2][:4] + bytes([bad[3][2][4] ^ 0x40]) + bad[3][2][5:])
    good = program.stream(image_b, first_tick=bad[-1][0] + 3)
    result = program.run(bad + good, good[-1][0] + 14)
    lines = [line for line in result.lines if not line.startswith("first ")]
    before, swap, after, _ = split(lines)
    last = [m.tick for m in result.rx if m.data == good[-1][2]][-1]
    print("Kilobot (simavr atmega328p, real kilolib, IR from the simavr board) running %s; %s (%d bytes) streamed "
          "twice as %d chunks (message type 0x%02x), one per kilolib tick: ticks %d..%d with chunk 3 corrupted, "
          "then ticks %d..%d intact" % (SUPERVISOR_A.stem, SUPERVISOR_B.stem, len(image_b), len(good),
                                        program.chunk_type, bad[0][0], bad[-1][0], good[0][0], good[-1][0]))
    shown = set(before[:3] + before[-3:] + after[:3] + after[-1:]) | {line for line in lines if not line[:1].isdigit()}
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
    print("%d steps of %s, then \"%s\" at the step after the last chunk came (tick %d), then %d steps of %s from its "
          "initial states; both traces equal the Python reference VM's: %s"
          % (len(before), SUPERVISOR_A.stem, swap, last, len(after), SUPERVISOR_B.stem,
             "yes" if same_a and same_b else "NO"))
    return 0 if swap and same_a and same_b and len(before) == Program.step_of(result.lines, last) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/kilobot/swap_demo"))
