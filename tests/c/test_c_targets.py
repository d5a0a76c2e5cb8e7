"""`swarmvm gen --target c` and `--target kilobot`: deterministic output, kept skeletons, and
programs that build and behave: the c target's control loop on the host, a controller written
against Nadzoru's C API (SCT_*) printing the reference trace, and a Kilobot application for
every corpus supervisor linked with the official flags, within 28,672 bytes of flash and 1 KB of
stack room, running in simavr."""

import re
import subprocess

import pytest

from conformance import c_harness
from conformance.cases import SUPERVISORS, Run, batch, reference
from swarmvm.pipeline import compile_inputs
from checkout import FIRMWARE

EXAMPLE = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
KILOBOT_FLASH, KILOBOT_SRAM, MIN_STACK = 28672, 2048, 1024


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
    subprocess.run(["make", "-s", "CFLAGS=%s -O2 -DSVM_STEPS=200" % " ".join(STRICT)], cwd=tmp_path, check=True,
                   capture_output=True)
    assert subprocess.run([str(tmp_path / "energy_worker")], timeout=10).returncode == 0


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


def kilobot_build(path, tmp_path):
    name = path.rsplit("/", 1)[-1][:-5]
    gen(path, "kilobot", tmp_path, name)
    flags = re.findall(r"-DSVM_[A-Z_]+=[A-Z_0-9]+", (tmp_path / "Makefile").read_text())
    elf = tmp_path / (name + ".elf")
    sources = [tmp_path / f for f in (name + "_app.c", name + "_controller.c", name + "_tables.c", "swarmvm.c")]
    subprocess.run(["avr-gcc", *c_harness.KILOBOT_FLAGS, *STRICT, *flags, "-I%s" % (FIRMWARE / "kilobot"),
                    *map(str, sources), str(FIRMWARE / "kilobot" / "kilolib_emu.c"), "-o", str(elf)],
                   check=True, capture_output=True, text=True)
    return elf


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_kilobot_application_fits_and_runs(path, tmp_path):
    elf = kilobot_build(path, tmp_path)
    sizes = dict((k, int(v)) for k, v in re.findall(r"^\.(text|data|bss)\s+(\d+)",
                 subprocess.run(["avr-size", "-A", str(elf)], capture_output=True, text=True).stdout, re.M))
    assert sizes["text"] + sizes.get("data", 0) <= KILOBOT_FLASH
    assert KILOBOT_SRAM - sizes.get("data", 0) - sizes.get("bss", 0) >= MIN_STACK
    output = c_harness.run_avr(elf)
    assert output.splitlines()[-1] == "end"        # kilo_start ran setup and every loop
    assert "color 3" not in output.splitlines()      # setup did not signal a refused image (red)


HOST_KILOLIB = r"""
/* Test-only host kilolib: kilo_start drives the generated application's message glue. */
#include <stdio.h>
#include <string.h>
#include "kilolib.h"
#include "nw_tables.h"

void nw_send(uint8_t event);   /* nw_app.c */

message_rx_t kilo_message_rx;
message_tx_t kilo_message_tx;
message_tx_success_t kilo_message_tx_success;
volatile uint32_t kilo_ticks;
uint16_t kilo_uid;
uint8_t kilo_turn_left, kilo_turn_right, kilo_straight_left, kilo_straight_right;

void kilo_init(void) {}
void set_motors(uint8_t l, uint8_t r) { (void)l; (void)r; }
void spinup_motors(void) {}
void set_color(uint8_t c) { printf("color %u\n", (unsigned)c); }
int16_t get_ambientlight(void) { return 0; }
int16_t get_voltage(void) { return 0; }
uint8_t estimate_distance(const distance_measurement_t *d) { (void)d; return 0; }
uint8_t rand_soft(void) { return 0; }
uint8_t rand_hard(void) { return 0; }
uint16_t message_crc(const message_t *m) { return (uint16_t)(m->data[0] + 1u); }
void delay(uint16_t ms) { (void)ms; }

void kilo_start(void (*setup)(void), void (*loop)(void))
{
    message_t in, *out;
    distance_measurement_t d = {0, 0};
    unsigned first, second;
    setup();
    memset(&in, 0, sizeof in);
    memcpy(in.data, "exchange", 8);
    in.type = NORMAL;
    kilo_message_rx(&in, &d);
    first = nw_check_received_exchange();
    second = nw_check_received_exchange();
    printf("exchange %u %u\n", first, second);
    printf("message %u\n", nw_check_received_message());
    printf("idle_tx %u\n", kilo_message_tx() == 0);
    nw_send(EV_relay);
    out = kilo_message_tx();
    printf("tx %.9s crc %u\n", (const char *)out->data, (unsigned)out->crc);
    kilo_message_tx_success();
    printf("after_success %u\n", kilo_message_tx() == 0);
    loop();
}
"""


def test_kilobot_messages_map_to_public_events(tmp_path):
    """Received message "x" makes EV__x occur once; a controllable public event queues its
    message until kilolib reports it sent (generated app glue, on the host)."""
    path = next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))
    gen(path, "kilobot", tmp_path, "nw")
    (tmp_path / "host_kilolib.c").write_text(HOST_KILOLIB)
    flags = re.findall(r"-DSVM_MAX_[A-Z_]+=[0-9]+", (tmp_path / "Makefile").read_text())
    subprocess.run(["gcc", *STRICT, *flags, "-I%s" % (FIRMWARE / "kilobot"), "nw_app.c", "nw_controller.c",
                    "nw_tables.c", "swarmvm.c", "host_kilolib.c", "-o", "app"], cwd=tmp_path, check=True,
                   capture_output=True, text=True)
    out = subprocess.run([str(tmp_path / "app")], capture_output=True, text=True, check=True).stdout.splitlines()
    assert out[:5] == ["exchange 1 0", "message 0", "idle_tx 1", "tx relay crc %d" % (ord("r") + 1),
                       "after_success 1"]
