"""`swarmvm gen --target c` and `--target kilobot`: deterministic output, kept skeletons, and
programs that build and behave: the c target's control loop on the host, a controller written
against Nadzoru's C API (SCT_*) printing the reference trace, and a Kilobot application for
every corpus supervisor built by its generated Makefile against the real kilolib, within the
Kilobot's flash and stack room (its target record's limits), running in simavr (the Kilobot board).
Each output is built by its record's build command (tests/target_builds.py)."""

import re
import subprocess

import pytest

from conformance import c_harness
from conformance.cases import SUPERVISORS, Run, batch, reference, supervisor_yaml
from corrupted import corrupt_compiled_in_image
from targets.kilobot.needs import board, board_or_skip, kilolib_or_skip
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS
from target_builds import build_in_place

EXAMPLE = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
KILOBOT = TARGETS["kilobot"].limits


def gen(path, target, outdir, name):
    subprocess.run(["swarmvm", "gen", path, "--target", target, "-o", str(outdir), "--name", name],
                   check=True, capture_output=True)
    return {p.name: p.read_bytes() for p in sorted(outdir.iterdir())}


@pytest.mark.parametrize("target", ["c", "kilobot"])
def test_generation_is_deterministic_and_keeps_the_controller(target, tmp_path):
    first = gen(EXAMPLE, target, tmp_path / "a", "energy_worker")
    second = gen(EXAMPLE, target, tmp_path / "b", "energy_worker")
    assert first == second
    assert {"energy_worker_tables.c", "energy_worker_tables.h", "energy_worker_controller.c", "swarmvm.c",
            "swarmvm.h", "Makefile"} <= set(first)
    assert b"/work/" not in b"".join(first.values())            # no absolute paths
    controller = tmp_path / "a" / "energy_worker_controller.c"
    controller.write_text("/* edited */\n")
    gen(EXAMPLE, target, tmp_path / "a", "energy_worker")
    assert controller.read_text() == "/* edited */\n"


def test_c_target_builds_and_runs_with_its_makefile(tmp_path):
    gen(EXAMPLE, "c", tmp_path, "energy_worker")
    build_in_place(TARGETS["c"], tmp_path, "energy_worker", "CFLAGS=%s -O2 -DSVM_STEPS=200" % " ".join(STRICT)).check_returncode()
    assert subprocess.run([str(tmp_path / "energy_worker")], timeout=10).returncode == 0
    assert subprocess.run([str(tmp_path / "energy_worker"), "1000"], timeout=10).returncode == 0
    refused = subprocess.run([str(tmp_path / "energy_worker"), "ten"], capture_output=True, text=True, timeout=10)
    assert refused.returncode == 2 and refused.stderr.startswith("usage: ")


def test_c_program_without_a_step_count_says_it_runs_until_stopped(tmp_path):
    gen(EXAMPLE, "c", tmp_path, "energy_worker")
    build_in_place(TARGETS["c"], tmp_path, "energy_worker").check_returncode()
    proc = subprocess.Popen([str(tmp_path / "energy_worker")], stderr=subprocess.PIPE, text=True)
    try:
        line = proc.stderr.readline()
        assert proc.poll() is None       # still stepping
    finally:
        proc.kill()
        proc.wait()
    assert line == "%s: stepping the VM until stopped (%s N stops after N steps)\n" % ((tmp_path / "energy_worker",) * 2)


SCT_CONTROLLER = r"""
/* A controller in the published OpenSwarm style: Nadzoru's C API, callbacks as they are. */
#include <stdio.h>
#include "energy_worker_tables.h"

static const unsigned char rows[][%(m)d] = {%(rows)s};
static int step;
static unsigned char fired[NUM_EVENTS + 1], nfired;
static const char *names[NUM_EVENTS] = {%(names)s};
static unsigned char events[NUM_EVENTS];

static unsigned char check_input(void *data)
{
    unsigned char e = *(unsigned char *)data;
    return (rows[step][e / 8] >> (e %% 8)) & 1;
}

static void callback(void *data)
{
    fired[nfired++] = *(unsigned char *)data;
}

int main(void)
{
    unsigned char e, k;
    SCT_init();
    for (e = 0; e < NUM_EVENTS; e++) {
        events[e] = e;
        SCT_add_callback(e, callback, check_input, &events[e]);
    }
    for (step = 0; step < %(steps)d; step++) {
        nfired = 0;
        SCT_run_step();
        printf("%%d ", step + 1);
        for (k = 0; k < nfired; k++) printf("%%s%%s", k ? "," : "", names[fired[k]]);
        if (nfired == 0) printf("-");
        for (k = 0; k < NUM_SUPERVISORS; k++) printf("%%s%%u", k ? "," : " ", (unsigned)svm_state(SCT_vm(), k));
        printf(" %%u\n", (unsigned)svm_violations(SCT_vm()));
    }
    return 0;
}
"""


def test_nadzoru_style_controller_prints_the_reference_trace(tmp_path):
    b = batch(EXAMPLE)
    gen(EXAMPLE, "c", tmp_path, "energy_worker")
    compiled = compile_inputs([EXAMPLE])
    m = b.image[13]
    rows = ", ".join("{%s}" % ", ".join(str(sum(1 << e for e in row) >> (8 * i) & 0xFF) for i in range(m))
                     for row in b.scripts[0])
    names = ", ".join('"EV_%s"' % n for n in compiled.model.events)
    (tmp_path / "published.c").write_text(SCT_CONTROLLER % dict(m=m, rows=rows, names=names, steps=len(b.scripts[0])))
    sources = ["published.c", "energy_worker_tables.c", "energy_worker_controller.c", "swarmvm.c", "swarmvm_sct.c"]
    subprocess.run(["gcc", *STRICT, *c_harness.limits(b), *sources, "-o", "published"], cwd=tmp_path, check=True,
                   capture_output=True)
    out = subprocess.run([str(tmp_path / "published")], capture_output=True, text=True, check=True).stdout
    assert out.splitlines() == reference(b, Run("level", "after-inputs", "uniform", 1, 0))


def kilobot_build(path, tmp_path, stream=False):
    """The generated Kilobot application, built by its own Makefile against the real kilolib
    (with the image receiver: `make STREAM=1`)."""
    name = path.rsplit("/", 1)[-1][:-5]
    gen(path, "kilobot", tmp_path, name)
    build_in_place(TARGETS["kilobot"], tmp_path, name, "KILOLIB=%s" % kilolib_or_skip(), "CPPFLAGS=-Wextra -Werror -pedantic",
                   *(["STREAM=1"] if stream else [])).check_returncode()
    return tmp_path / (name + ".elf")


RED = 3     # RGB(3, 0, 0): the application's "image refused"


@pytest.mark.emulator
@pytest.mark.parametrize("stream", (False, True), ids=("flash-only", "stream"))
@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_kilobot_application_fits_and_runs(path, stream, tmp_path):
    board_or_skip()
    elf = kilobot_build(path, tmp_path, stream)
    sizes = dict((k, int(v)) for k, v in re.findall(r"^\.(text|data|bss)\s+(\d+)",
                 subprocess.run(["avr-size", "-A", str(elf)], capture_output=True, text=True).stdout, re.M))
    assert KILOBOT is not None
    assert sizes["text"] + sizes.get("data", 0) <= KILOBOT.flash
    assert KILOBOT.sram - sizes.get("data", 0) - sizes.get("bss", 0) >= KILOBOT.min_stack
    run = board.run(elf, ticks=40, read="last_step")
    # Started by RUN, the VM steps at every kilolib tick to the end (last_step: the tick of the
    # runtime's last step), and setup never signalled a refused image.
    assert run.end[:1] == (40,) and run.ram >= 39
    assert RED not in [colour for tick, colour in run.leds if tick > run.rx[0].tick]


def test_a_corrupted_compiled_in_image_is_refused_at_start_up_on_the_host(tmp_path):
    gen(EXAMPLE, "c", tmp_path, "energy_worker")
    corrupt_compiled_in_image(tmp_path / "energy_worker_tables.c")
    build_in_place(TARGETS["c"], tmp_path, "energy_worker").check_returncode()
    run = subprocess.run([str(tmp_path / "energy_worker"), "10"], capture_output=True, text=True, timeout=10)
    assert run.returncode == 1 and run.stdout == ""
    assert run.stderr == ("%s: the compiled-in table image was refused (swarmvm error 4: its checksum does not "
                          "match, the image is corrupted)\n" % (tmp_path / "energy_worker"))


@pytest.mark.emulator
def test_a_corrupted_compiled_in_image_halts_the_kilobot_in_red(tmp_path):
    """On the Kilobot board in simavr: the refused image shows red from set-up on, and the VM,
    holding no image, fires nothing: the LED never changes again (a running controller shows
    each fired event's colour, test_kilobot_application_fits_and_runs) and nothing is sent."""
    board_or_skip()
    name = "energy_worker"
    gen(EXAMPLE, "kilobot", tmp_path, name)
    corrupt_compiled_in_image(tmp_path / (name + "_tables.c"))
    build_in_place(TARGETS["kilobot"], tmp_path, name, "KILOLIB=%s" % kilolib_or_skip()).check_returncode()
    run = board.run(tmp_path / (name + ".elf"), ticks=40)
    assert run.end[:1] == (40,)
    colours = [colour for _, colour in run.leds]      # kilolib's start-up colours, then set-up's
    assert RED in colours and colours[colours.index(RED):] == [RED] and run.tx == []


# Names that gave C which did not compile (issue 12): an event `stream` (the Kilobot stream hook
# was <model>_on_stream, the action of such an event), `x` beside `received_x`, and a model
# name that is not ASCII (avr-gcc refuses such identifiers; it becomes ouvri_re).
AWKWARD_EVENTS = ["stream", "_stream", "x", "received_x"]
AWKWARD = supervisor_yaml(AWKWARD_EVENTS, [1, 0, 1, 0], [set(AWKWARD_EVENTS)], [[[(e, 0) for e in AWKWARD_EVENTS]]],
                          public=[1, 1, 0, 0])


@pytest.mark.parametrize("stem", ["stream", "ouvrière"])
def test_awkward_names_compile_for_the_kilobot_and_the_host(stem, tmp_path):
    model = tmp_path / (stem + ".yaml")
    model.write_text(AWKWARD)
    name = "ouvri_re" if stem == "ouvrière" else stem
    for stream in (False, True):
        out = tmp_path / ("kilobot_stream" if stream else "kilobot")
        subprocess.run(["swarmvm", "gen", str(model), "--target", "kilobot", "-o", str(out)], check=True,
                       capture_output=True)
        build = build_in_place(TARGETS["kilobot"], out, name, "KILOLIB=%s" % kilolib_or_skip(),
                               "CPPFLAGS=-Wextra -Werror -pedantic", *(["STREAM=1"] if stream else []))
        assert build.returncode == 0 and (out / (name + ".elf")).is_file(), build.stderr
    host = tmp_path / "c"
    subprocess.run(["swarmvm", "gen", str(model), "--target", "c", "-o", str(host)], check=True, capture_output=True)
    build = build_in_place(TARGETS["c"], host, name, "CFLAGS=%s -O2 -DSVM_STEPS=20" % " ".join(STRICT))
    assert build.returncode == 0, build.stderr
    assert subprocess.run([str(host / name)], timeout=10).returncode == 0
