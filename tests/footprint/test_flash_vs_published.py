"""swarmvm's minimal profile (SVM_TRUSTED_IMAGE, runtime_c/README.md) beside the published VM:
benchmarks/flash_vs_published.py run on two corpus supervisors, the smallest and the energy
worker of issue 35 (flash, RAM, and the cost of a step: cycles in simavr, instructions in QEMU),
and on every corpus supervisor (flash); the benchmark failing when the two VMs do not take the
same transitions; and the profile itself, which must step exactly as the validating VM does and
must never run bytes that are not the generator's image; with its options fixed at build, no
violation counter and no public-first pass (the benchmark's build) it must step as the
validating VM given the same options."""

import dataclasses
import importlib.util
import shutil
import subprocess
from pathlib import Path

import pytest

from swarmvm.api import compile_model
from swarmvm.targets.values import has_public_inputs

ROOT = Path(__file__).resolve().parents[2]
RUNTIME = ROOT / "runtime_c"
SUPERVISORS = [ROOT / "tests/corpus/openswarm/capbot_demo.yaml", ROOT / "tests/corpus/openswarm/energy_worker.yaml"]
TOOLS = ("avr-gcc", "avr-size", "avr-nm", "arm-none-eabi-gcc", "arm-none-eabi-size", "arm-none-eabi-nm", "simavr",
         "qemu-system-arm")
TWO_ENABLED = ROOT / "tests/corpus/nadzoru2/probabilistic_example.yaml"
NETWORK_WORKER = ROOT / "tests/corpus/openswarm/network_worker.yaml"


def _benchmark():
    spec = importlib.util.spec_from_file_location("flash_vs_published", ROOT / "benchmarks" / "flash_vs_published.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _require(tools):
    missing = [t for t in tools if shutil.which(t) is None]
    if missing:
        pytest.fail("needed for the comparison, not on the PATH: %s (make setup)" % ", ".join(missing))


@pytest.fixture(scope="module")
def rows(tmp_path_factory):
    _require(TOOLS)
    bench = _benchmark()
    return bench.bench(SUPERVISORS, [bench.avr(), bench.arm()], tmp_path_factory.mktemp("flash_vs_published"))


@pytest.mark.emulator
def test_ram_and_cost_per_step_below_the_published_vm(rows):
    """RAM on both toolchains; per step, the mean and the worst: cycles on the ATmega328P
    (simavr), instructions on the Cortex-M4F (QEMU -icount), over the same script, both VMs
    having taken the same transitions (the benchmark checks it; the figures are the reference's)."""
    assert [(r.toolchain, r.step_unit) for r in rows] == [("avr", "cycles"), ("arm", "instructions")] * 2
    for row in rows:
        assert row.swarmvm_ram < row.published_ram, row
        assert row.swarmvm_step < row.published_step, row
        assert row.swarmvm_worst < row.published_worst, row
    by_supervisor = {}
    for row in rows:
        by_supervisor.setdefault(row.supervisor, set()).add((row.fired, row.digest))
    assert all(len(runs) == 1 and next(iter(runs))[0] > 0 for runs in by_supervisor.values()), by_supervisor


@pytest.mark.emulator
def test_flash_below_the_published_vm(rows):
    """Met on these two (capbot_demo and energy_worker, on both toolchains)."""
    for row in rows:
        assert row.swarmvm_flash < row.published_flash, row


@pytest.mark.emulator
def test_a_published_program_over_the_kilobots_sram_is_timed_on_the_roomier_avr(tmp_path):
    """network_worker's published tables (2,704 B) do not fit the ATmega328P's SRAM: its cost
    per step comes from the ATmega1284P, on which swarmvm's program, run there too, takes the
    very cycles it takes on the 328P (the same core: the substitution changes no figure), and
    the row compares the two VMs over the same transitions."""
    _require(TOOLS)
    bench = _benchmark()
    tc = bench.avr()
    sup = bench.Supervisor(NETWORK_WORKER, tmp_path, bench.PROFILE)
    assert [sup.build(tc, side, cycles=False) for side in ("published", "swarmvm")]
    assert sup.overflows == {("avr", "published")}
    on = {mcu: bench.parse_steps(elf, bench.simavr_output(elf, mcu))
          for mcu in (bench.KILOBOT_MCU, bench.ROOMY_MCU)
          for elf in [sup.build(tc, "swarmvm", cycles=True, mcu=mcu)]}
    assert on[bench.KILOBOT_MCU] == on[bench.ROOMY_MCU]
    (tmp_path / "row").mkdir()
    [row] = bench.bench([NETWORK_WORKER], [tc], tmp_path / "row")
    assert row.published_overflows and row.published_step is not None
    assert row.swarmvm_step < row.published_step and row.swarmvm_worst < row.published_worst, row
    assert "(on the atmega1284p)" in bench.table([row])


@pytest.mark.emulator
@pytest.mark.parametrize("toolchain", ["avr", "arm"])
def test_other_transitions_fail_the_benchmark(monkeypatch, capsys, toolchain):
    """The published side's generator replays swarmvm's choices; shifted by one position, the
    published VM chooses the other event where two are enabled (probabilistic_example has two
    at 177 of its 500 steps): the run must fail, saying so, with no table."""
    _require(TOOLS)
    bench = _benchmark()
    expected = bench.same_steps.expected

    def shifted(*args, **kwargs):
        right = expected(*args, **kwargs)
        return dataclasses.replace(right, draws=tuple(d + 1 for d in right.draws))

    monkeypatch.setattr(bench.same_steps, "expected", shifted)
    assert bench.main([str(TWO_ENABLED), "--toolchain", toolchain]) == 1
    out, err = capsys.readouterr()
    assert "cannot measure: probabilistic_example/%s: the published VM and swarmvm took different transitions" % toolchain in err
    assert "|" not in out


@pytest.mark.emulator
def test_both_vms_off_the_reference_fail_the_benchmark(monkeypatch, capsys):
    """Two VMs that agree with each other but not with the reference VM fail it too."""
    _require(TOOLS)
    bench = _benchmark()
    expected = bench.same_steps.expected
    monkeypatch.setattr(bench.same_steps, "expected",
                        lambda *a, **k: dataclasses.replace(expected(*a, **k), digest=expected(*a, **k).digest ^ 1))
    assert bench.main([str(SUPERVISORS[0]), "--toolchain", "arm"]) == 1
    assert "capbot_demo/arm: both VMs took other transitions than the reference VM" in capsys.readouterr().err


@pytest.fixture(scope="module")
def corpus_rows(tmp_path_factory):
    _require(TOOLS[:6])
    bench = _benchmark()
    return bench.bench(bench.CORPUS, [bench.avr(), bench.arm()], tmp_path_factory.mktemp("flash_corpus"), cycles=False)


def test_flash_below_the_published_vm_on_every_corpus_supervisor(corpus_rows):
    """Issue 35's target, point 4: every corpus supervisor, both toolchains (flash only, no
    simulator), swarmvm's generator counted."""
    assert len(corpus_rows) == 2 * len(_benchmark().CORPUS)
    worse = {(r.toolchain, r.supervisor): "%d >= %d" % (r.swarmvm_flash, r.published_flash)
             for r in corpus_rows if r.swarmvm_flash >= r.published_flash}
    assert not worse, worse


# ---- the profile itself (host gcc) ---------------------------------------------------------

STEPPER = r"""
#include <stdio.h>
#include "swarmvm.h"
extern const uint8_t bench_image[];
static svm_vm_t vm;
static uint32_t inputs = 12345u;
static uint8_t dispatch(svm_vm_t *machine, uint8_t event, uint8_t op)
{
    (void)machine;
    return (uint8_t)(op == SVM_OP_CHECK ? (inputs >> (event & 31u)) & 1u : 0u);
}
int main(void)
{
    static const uint8_t other[4] = {0x53, 0x56, 0x4d, 0x49};
    int step, s;
    svm_init(&vm);
    svm_set_dispatch(&vm, dispatch);
    printf("other refused as not the image: %d\n", svm_load_P(&vm, other, sizeof other) == SVM_ERR_SOURCE);
    step = svm_load_P(&vm, bench_image, BENCH_IMAGE_SIZE);
    printf("load %d, over the limits %d\n", step, step == SVM_ERR_LIMITS);
    if (step != SVM_OK) {
        return 0;
    }
    for (step = 0; step < 3000; step++) {
#ifdef FIXED_OPTIONS
        svm_set_options(&vm, FIXED_OPTIONS, 7u);            /* the build's (SVM_TRUSTED_OPTIONS) */
#else
        svm_set_options(&vm, (uint8_t)(step / 250), 7u);    /* inputs x control x policy */
#endif
        if (step % 250 == 0) {
            svm_reset(&vm);
        }
        inputs ^= inputs << 13; inputs ^= inputs >> 17; inputs ^= inputs << 5;
        printf("%u", svm_step(&vm));
        for (s = 0; s < svm_num_supervisors(&vm); s++) {
            printf(" %u", svm_state(&vm, (uint8_t)s));
        }
#if SVM_WITH_VIOLATIONS
        printf(" %lu", (unsigned long)svm_violations(&vm));
#endif
        printf("\n");
    }
    return 0;
}
"""


def _host_run(tmp_path: Path, supervisor: Path, trusted: bool, more_states: int = 0, flags: tuple = (),
              trusted_flags: tuple = ()) -> str:
    """The stepper's output; `flags` go to both builds, `trusted_flags` to the trusted one only."""
    compiled = compile_model([str(supervisor)], names=False)
    t = compiled.tables
    folder = tmp_path / (("trusted" if trusted else "validating") + "".join(flags).replace("-D", "_").replace("=", ""))
    folder.mkdir()
    (folder / "main.c").write_text(STEPPER)
    (folder / "tables.c").write_text('#include "swarmvm.h"\nconst uint8_t bench_image[%d] SVM_PROGMEM = {%s};\n'
                                     % (len(compiled.image), ",".join(map(str, compiled.image))))
    limits = ["-DSVM_MAX_EVENTS=%d" % t.num_events, "-DSVM_MAX_SUPERVISORS=%d" % t.num_supervisors,
              "-DSVM_MAX_STATES=%d" % (t.num_states + more_states), "-DBENCH_IMAGE_SIZE=%du" % len(compiled.image)]
    profile = ["-DSVM_TRUSTED_IMAGE=bench_image", *trusted_flags] if trusted else ["-DSVM_MASK_EXACT=1"]
    exe = folder / "stepper"
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2", *limits, *profile,
                    "-DSVM_WITH_BINDINGS=0", "-DSVM_WITH_NAMES=0", "-DSVM_WITH_LEARNED=0", *flags, "-I", str(RUNTIME),
                    str(folder / "main.c"), str(folder / "tables.c"), str(RUNTIME / "swarmvm.c"), "-o", str(exe)],
                   check=True, capture_output=True, text=True)
    return subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout


@pytest.mark.parametrize("supervisor", [ROOT / "tests/corpus/openswarm/network_worker.yaml",
                                        ROOT / "tests/corpus/nadzoru2/probabilistic_example.yaml",
                                        ROOT / "tests/corpus/openswarm/energy_worker.yaml"], ids=lambda p: p.stem)
@pytest.mark.parametrize("table", ["1", "0"], ids=["popcount-table", "popcount-loop"])
def test_trusted_profile_steps_as_the_validating_vm(tmp_path, supervisor, table):
    """Every option combination the stepper cycles through (inputs, control, policies first and
    weighted included): the same events fired, states and violations at every step; with the
    popcount table of the host build and with the bit-clearing count the AVR (-Os) and Cortex-M4
    builds use instead."""
    flags = ("-DSVM_POPCOUNT_TABLE=" + table,)
    trusted = _host_run(tmp_path, supervisor, True, flags=flags)
    validating = _host_run(tmp_path, supervisor, False, flags=flags)
    assert trusted.splitlines()[1] == "load 0, over the limits 0"
    assert len(trusted.splitlines()) == 3002
    assert trusted.splitlines()[1:] == validating.splitlines()[1:]


# The options the profile may fix at build (SVM_TRUSTED_OPTIONS): level and edge inputs, after-inputs
# and if-quiet control, the uniform, first and weighted policies.
FIXED = ["0x00u", "0x01u", "0x02u", "0x03u", "0x05u", "0x0Bu"]


@pytest.mark.parametrize("supervisor", [ROOT / "tests/corpus/openswarm/network_worker.yaml",
                                        ROOT / "tests/corpus/nadzoru2/probabilistic_example.yaml",
                                        ROOT / "tests/corpus/openswarm/energy_worker.yaml",
                                        ROOT / "tests/corpus/openswarm/hitl_leader.yaml",
                                        ROOT / "tests/corpus/nadzoru2/public_example.yaml",
                                        ROOT / "tests/corpus/openswarm/network_leader.yaml"], ids=lambda p: p.stem)
def test_smallest_profile_steps_as_the_validating_vm(tmp_path, supervisor):
    """The benchmark's profile (options fixed at build, no violation counter, no public-first pass
    for a model without public uncontrollable events: public_example and network_leader, whose
    public events are all controllable, run without it) fires the same events and reaches the
    same states at every step as the validating VM given the same options at run time; with the
    bit-clearing popcount the benchmark's builds (-Os on AVR, the Cortex-M4) use."""
    has_public = has_public_inputs(compile_model([str(supervisor)], names=False).tables)
    trusted_flags = ("-DSVM_TRUSTED_OPTIONS=%s" % FIXED[0],) + (() if has_public else ("-DSVM_WITH_PUBLIC=0",))
    for options in FIXED:
        flags = ("-DFIXED_OPTIONS=%s" % options, "-DSVM_WITH_VIOLATIONS=0", "-DSVM_POPCOUNT_TABLE=0")
        trusted = _host_run(tmp_path, supervisor, True, flags=flags,
                            trusted_flags=(trusted_flags[0].replace(FIXED[0], options),) + trusted_flags[1:])
        validating = _host_run(tmp_path, supervisor, False, flags=flags)
        assert trusted.splitlines()[1] == "load 0, over the limits 0", options
        assert len(trusted.splitlines()) == 3002
        assert trusted.splitlines()[1:] == validating.splitlines()[1:], options


def test_profile_without_public_pass_refuses_an_image_with_public_inputs(tmp_path):
    """hitl_leader has a public uncontrollable event (its event 0), which the public-first pass
    polls first: a build without the pass must not run it."""
    supervisor = ROOT / "tests/corpus/openswarm/hitl_leader.yaml"
    assert has_public_inputs(compile_model([str(supervisor)], names=False).tables)
    out = _host_run(tmp_path, supervisor, True, trusted_flags=("-DSVM_WITH_PUBLIC=0",))
    assert out.splitlines()[1:] == ["load %d, over the limits 1" % int(out.splitlines()[1].split()[1].rstrip(","))]


def test_without_public_pass_only_in_the_profile(tmp_path):
    program = tmp_path / "p.c"
    program.write_text('#include "swarmvm.h"\nint main(void) { return 0; }\n')
    result = subprocess.run(["gcc", "-std=c99", "-DSVM_WITH_PUBLIC=0", "-I", str(RUNTIME), "-c", str(program), "-o",
                             str(tmp_path / "p.o")], capture_output=True, text=True)
    assert result.returncode != 0 and "SVM_WITH_PUBLIC=0 is for the minimal profile" in result.stderr


def test_trusted_profile_refuses_any_other_image(tmp_path):
    out = _host_run(tmp_path, SUPERVISORS[0], True)
    assert out.splitlines()[0] == "other refused as not the image: 1"


def test_trusted_profile_refuses_its_image_under_other_limits(tmp_path):
    """The step takes the build's limits for the image's counts: a build whose limits are not
    the image's exact ones (here one state more) must not run it."""
    out = _host_run(tmp_path, SUPERVISORS[1], True, more_states=1)
    assert out.splitlines()[1:] == ["load %d, over the limits 1" % int(out.splitlines()[1].split()[1].rstrip(","))]


@pytest.mark.parametrize("call", ["svm_load(&vm, buffer, sizeof buffer)", "svm_load_E(&vm, buffer, sizeof buffer)",
                                  "svm_validate(buffer, sizeof buffer, 0)"])
def test_trusted_profile_has_no_loader_of_other_bytes(tmp_path, call):
    """Bytes from a stream, RAM or EEPROM cannot reach a trusted build's VM: it does not compile."""
    program = tmp_path / "p.c"
    program.write_text('#include "swarmvm.h"\nstatic svm_vm_t vm;\nstatic uint8_t buffer[64];\n'
                       "int main(void) { svm_init(&vm); return %s; }\n" % call)
    result = subprocess.run(["gcc", "-std=c99", "-Werror=implicit-function-declaration", "-DSVM_TRUSTED_IMAGE=img",
                             "-I", str(RUNTIME), "-c", str(program), "-o", str(tmp_path / "p.o")],
                            capture_output=True, text=True)
    assert result.returncode != 0 and "implicit declaration" in result.stderr


def test_trusted_profile_needs_the_flash_image_settings(tmp_path):
    program = tmp_path / "p.c"
    program.write_text('#include "swarmvm.h"\nint main(void) { return 0; }\n')
    for flags in (["-DSVM_MASK_EXACT=0"], ["-DSVM_IMAGE_SOURCES=SVM_FLASH_OR_RAM"]):
        result = subprocess.run(["gcc", "-std=c99", "-DSVM_TRUSTED_IMAGE=img", *flags, "-I", str(RUNTIME), "-c",
                                 str(program), "-o", str(tmp_path / "p.o")], capture_output=True, text=True)
        assert result.returncode != 0 and "SVM_TRUSTED_IMAGE runs the generator's image" in result.stderr
