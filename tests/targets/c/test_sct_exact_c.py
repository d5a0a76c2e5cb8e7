"""The C API's exact mode (runtime_c/swarmvm_sct.h, SVM_SCT_EXACT=1) is the published generic C
VM's step, bit for bit (issue 35; docs/compat.md, "C"): on every corpus supervisor
one driver (sct_driver.c: 10,000 steps of contradictory inputs, several checks true together and
toggling, srand(seed) on both sides, a reset and a NULL registration on the way) prints the same
log on the published-form VM (benchmarks/published_form/) and on swarmvm: the same checks called
in the same order, the same callbacks (events applied) in the same order, every supervisor's
state in the file's numbering. The published-form VM is itself checked against the real
published file (FreeBot's sct_work_and_charge.c), and canonical mode is shown to differ."""

import re
import shutil
import subprocess

import pytest

from conformance.cases import SUPERVISORS
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets.c import file_order
from targets.c import sct_builds as b

STEPS = 10_000
SEED = 20260412
PUBLISHED_FILE = b.REFERENCE / "src" / "sct_work_and_charge.c"
EXAMPLE = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))
# A model where several controllable events are often enabled together, so that the draw shows.
CHOOSING = next(p for p in SUPERVISORS if p.endswith("/network_worker.yaml"))
needs_reference = pytest.mark.skipif(not PUBLISHED_FILE.is_file(), reason="needs ../shared/reference beside the checkout")
# One log line: "k: c<ev>... a<ev>... | s <state>...", and the lines "reset" and "unbind 0".
STEP = re.compile(r"(\d+):((?: [ca]\d+)*) \| s((?: \d+)+)\Z")


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """The 10,000-line log of a default build, built and run once for the module:
    ``logs("published" | "exact" | "canonical", supervisor)``, ``logs("real")`` (the published file)."""
    cache = {}

    def log(kind, supervisor=None):
        if (kind, supervisor) not in cache:
            folder = tmp_path_factory.mktemp(kind)
            binary = (b.real_published(folder) if kind == "real" else
                      b.published_form(b.ROOT / supervisor, folder) if kind == "published" else
                      b.swarmvm(b.ROOT / supervisor, folder, exact=kind == "exact"))
            cache[kind, supervisor] = b.run(binary, STEPS, SEED)
        return cache[kind, supervisor]
    return log


def _stem(path: str) -> str:
    return path.split("/")[-1][:-5]


def applied(line: str) -> list[str]:
    return re.findall(r"a\d+", line)


def test_the_published_form_vm_is_the_published_vm(logs, tmp_path):
    """The oracle first: the published-form VM given the published file's tables prints, for
    the same driver, the same 10,000 lines as the published file itself."""
    if not PUBLISHED_FILE.is_file():
        pytest.skip("needs ../shared/reference beside the checkout")
    real = logs("real")
    mine = b.run(b.real_published(tmp_path / "form", vm=b.PUBLISHED_VM), STEPS, SEED)
    assert len(real) == STEPS + 2 and mine == real


@pytest.mark.parametrize("supervisor", SUPERVISORS, ids=_stem)
def test_exact_mode_logs_are_the_published_vms(supervisor, logs):
    published, exact = logs("published", supervisor), logs("exact", supervisor)
    assert len(exact) == STEPS + 2
    for k, (want, got) in enumerate(zip(published, exact)):
        assert got == want, "first difference at line %d" % k
    assert exact == published
    # The script is contradictory: some step applies two or more events (inputs together).
    assert max(len(applied(line)) for line in exact) >= 2


@needs_reference
def test_exact_mode_runs_the_published_file_as_published(logs, tmp_path):
    """swarmvm generated from the published C file itself (its own tables, the header named as
    its program includes it: gen --sct-header) against that file's own VM."""
    real = logs("real")
    exact = b.swarmvm(PUBLISHED_FILE, tmp_path / "swarmvm", exact=True, sct_header="sct_work_and_charge.h")
    assert b.run(exact, STEPS, SEED) == real


def test_exact_mode_in_the_minimal_profile(logs, tmp_path):
    """The same log with the image trusted (SVM_TRUSTED_IMAGE: runtime_c/README.md, "The minimal
    profile"), the build a flash-tight robot uses."""
    binary = b.swarmvm(b.ROOT / EXAMPLE, tmp_path, exact=True, defines=("-DSVM_TRUSTED_IMAGE=model_image",))
    assert b.run(binary, STEPS, SEED) == logs("published", EXAMPLE)


def test_a_start_state_other_than_the_initial_one(tmp_path):
    """SCT_init starts where the file's sup_current_state says, SCT_reset at sup_init_state,
    as published (the driver resets half way)."""
    text = (b.ROOT / EXAMPLE).read_text()
    moved = tmp_path / "moved.yaml"
    moved.write_text(re.sub(r"sup_current_state: \[[^]]*\]", "sup_current_state: [ 3,2,1,0 ]", text))
    published = b.run(b.published_form(moved, tmp_path / "published"), STEPS, SEED)
    exact = b.run(b.swarmvm(moved, tmp_path / "swarmvm", exact=True), STEPS, SEED)
    assert exact == published
    assert not exact[0].endswith("| s 0 0 0 0")


def test_the_draw_comes_from_the_generator_given(logs, tmp_path):
    """SVM_SCT_RANDOM=fn at compile time and SCT_set_random(fn) at run time both draw from fn,
    as the published VM built with its RANDOM as fn; SCT_set_random(NULL) restores rand."""
    source = tmp_path / "lcg.c"
    source.write_text("static unsigned long x = 7;\nunsigned int lcg(void);\n"
                      "unsigned int lcg(void) { x = (x * 1103515245ul + 12345ul) & 0x7ffffffful; return (unsigned)(x >> 8); }\n")
    typed = ("-DSCT_RANDOM=lcg", "-DSCT_RANDOM_TYPE=unsigned int")
    published = b.run(b.published_form(b.ROOT / CHOOSING, tmp_path / "p", defines=typed + (str(source),)), STEPS, SEED)
    default = logs("published", CHOOSING)
    assert published != default
    at_build = b.swarmvm(b.ROOT / CHOOSING, tmp_path / "s1", exact=True, extra=(source,),
                         defines=("-DSVM_SCT_RANDOM=lcg", "-DSVM_SCT_RANDOM_TYPE=unsigned int"))
    at_run = b.swarmvm(b.ROOT / CHOOSING, tmp_path / "s2", exact=True, extra=(source,), defines=("-DDRIVER_SET_RANDOM=lcg",))
    restored = b.swarmvm(b.ROOT / CHOOSING, tmp_path / "s3", exact=True, extra=(source,),
                         defines=("-DDRIVER_SET_RANDOM=lcg", "-DDRIVER_RESTORE_RANDOM"))
    assert b.run(at_build, STEPS, SEED) == published
    assert b.run(at_run, STEPS, SEED) == published
    assert b.run(restored, STEPS, SEED) == default


def test_a_null_registration_replaces(logs):
    """SCT_add_callback(e, NULL, NULL, NULL) silences e (the driver does it at 3/4 of the run):
    its check and callback appear before, never after, on both VMs alike (the test above)."""
    exact = logs("exact", EXAMPLE)
    cut = exact.index("unbind 0")
    before, after = " ".join(exact[:cut]), " ".join(exact[cut:])
    assert re.search(r" [ca]0\b", before) and not re.search(r" [ca]0\b", after)


def _in_file_numbers(line: str, index: list[int], states: list[int], first: tuple[int, ...]) -> str:
    """A canonical-mode log line with events and states renumbered as the file numbers them."""
    match = STEP.match(line)
    if match is None:
        return line
    events = " ".join(t[0] + str(index[int(t[1:])]) for t in match.group(2).split())
    local = [int(n) for n in match.group(3).split()]
    numbered = " ".join(str(states[first[s] + n]) for s, n in enumerate(local))
    return "%s: %s | s %s" % (match.group(1), events, numbered)


def test_canonical_mode_still_differs(logs):
    """SVM_SCT_EXACT=0 (the default) is swarmvm's own step: even renumbered as the file numbers
    events and states, it polls in another order (public first, then by name) and applies and
    draws otherwise (its own generator), so the logs differ; the events polled are the same."""
    published, canonical = logs("published", EXAMPLE), logs("canonical", EXAMPLE)
    compiled = compile_inputs([str(b.ROOT / EXAMPLE)])
    order = file_order(compiled)
    states = [int.from_bytes(order["file_states"][i:i + 2], "little") for i in range(0, len(order["file_states"]), 2)]
    renumbered = [_in_file_numbers(line, order["file_index"], states, compiled.tables.sup_first_state)
                  for line in canonical]
    # (until the driver unbinds its event 0, which is another event in each numbering)
    cut = published.index("unbind 0")
    checks = [sorted(re.findall(r"c\d+", line)) for line in published[:cut]]
    assert [sorted(re.findall(r"c\d+", line)) for line in renumbered[:cut]] == checks
    differing = sum(a != b for a, b in zip(renumbered[:cut], published))
    assert differing > STEPS // 10, differing


def test_a_refused_image_is_reported_and_the_vm_does_nothing(tmp_path):
    """Built with SVM_MASK_EXACT=1 and the default SVM_MAX_EVENTS (64: 8-byte masks), the
    10-event image (2-byte masks) is refused: SCT_init returns the code, SCT_status says it, and
    the run that follows calls no check, no callback, and reports every state 0."""
    folder = tmp_path / "s"
    binary = b.swarmvm(b.ROOT / EXAMPLE, folder, exact=True)
    flags = [f for f in b.limits(folder) if not f.startswith("-DSVM_MAX_EVENTS")]
    refused = folder / "refused"
    b.compile_c([*b.CC, *b.STRICT, *flags, "-DSVM_MASK_EXACT=1", "-DSVM_SCT_EXACT=1", "-DDRIVER_SCT_STATE",
                 '-DSCT_HEADER="model_tables.h"', "-I%s" % folder, str(b.DRIVER),
                 *(str(folder / f) for f in ("model_tables.c", "swarmvm.c", "swarmvm_sct.c")), "-o", str(refused)],
                folder)
    out = subprocess.run([str(refused), "200", "1"], capture_output=True, text=True)
    lines = out.stdout.splitlines()
    code = re.match(r"SCT_init refused: (\d+), SCT_status (\d+)\Z", lines[0])
    assert out.returncode == 1 and code and code.group(1) == code.group(2) != "0"
    assert all(STEP.match(line).group(2) == "" and line.endswith("| s 0 0 0 0") for line in lines[1:] if STEP.match(line))
    assert b.run(binary, 5, 1)[0] != lines[1]     # the same build, image accepted, does step


def test_svm_bind_keeps_an_action_given_null(tmp_path):
    """The SCT layer replaces; svm_bind keeps its documented behaviour for its own users: a NULL
    action or check leaves the one bound before (so that the two can be bound separately)."""
    folder = tmp_path / "s"
    b.swarmvm(b.ROOT / EXAMPLE, folder, exact=False)
    program = folder / "bind.c"
    program.write_text("""#include <stdio.h>
#include "model_tables.h"
static int called;
static void action(void *data) { (void)data; called++; }
int main(void)
{
    svm_vm_t *vm;
    svm_binding_t *before;
    if (SCT_init() != SVM_OK) return 2;
    vm = SCT_vm();
    before = &vm->bindings[EV_moveToCharge];
    svm_bind(vm, EV_moveToCharge, action, NULL, NULL);
    svm_bind(vm, EV_moveToCharge, NULL, NULL, NULL);
    printf("%d\\n", before->action == action);
    SCT_add_callback(EV_moveToCharge, NULL, NULL, NULL);
    printf("%d\\n", before->action == NULL);
    return 0;
}
""")
    b.compile_c([*b.CC, *b.STRICT, *b.limits(folder), "-I%s" % folder, str(program),
                 *(str(folder / f) for f in ("model_tables.c", "swarmvm.c", "swarmvm_sct.c")), "-o", "bind"], folder)
    assert subprocess.run([str(folder / "bind")], capture_output=True, text=True).stdout == "1\n1\n"


def test_the_header_is_self_contained(tmp_path):
    """swarmvm_sct.h alone declares what a published program uses: NULL (<stdlib.h>) and rand."""
    program = tmp_path / "p.c"
    program.write_text('#include "swarmvm_sct.h"\nint f(void);\nint f(void) { void *p = NULL; (void)p; return rand(); }\n')
    b.compile_c([*b.CC, *b.STRICT, "-I%s" % b.RUNTIME_C, "-c", str(program), "-o", "p.o"], tmp_path)


@pytest.mark.parametrize("exact", [0, 1])
@pytest.mark.skipif(shutil.which("avr-gcc") is None, reason="needs avr-gcc")
def test_the_kilobot_build_compiles_without_warning(exact, tmp_path):
    """Both modes for the ATmega328P as the Kilobot builds it (flash-only image, exact masks,
    kilolib's rand_soft as the draw), under the strict flags."""
    b.swarmvm(b.ROOT / EXAMPLE, tmp_path, exact=True)
    for source in ("model_tables.c", "swarmvm.c", "swarmvm_sct.c"):
        b.compile_c(["avr-gcc", "-mmcu=atmega328p", "-Os", *b.STRICT, *b.limits(tmp_path), "-DSVM_MASK_EXACT=1",
                     "-DSVM_IMAGE_SOURCES=SVM_FLASH_ONLY", "-DSVM_SCT_EXACT=%d" % exact, "-DSVM_SCT_RANDOM=rand_soft",
                     "-c", source, "-o", source + ".o"], tmp_path)


@pytest.mark.parametrize("name", ["sct work.h", "sct_work", "CON.h", "swarmvm_sct.h", "model_tables.h", "9x.h",
                                  "../x.h", "x\x1b[2J.h"])
def test_a_bad_sct_header_name_is_one_line_and_exit_2(name, tmp_path):
    out = subprocess.run(["swarmvm", "gen", str(b.ROOT / EXAMPLE), "--target", "c", "--name", "model", "-o",
                          str(tmp_path / "out"), "--sct-header", name], capture_output=True, text=True)
    assert out.returncode == 2 and out.stdout == ""
    assert len(out.stderr.splitlines()) == 1 and "--sct-header" in out.stderr and "\x1b" not in out.stderr
    assert not (tmp_path / "out").exists()


def test_sct_header_is_for_the_c_targets(tmp_path):
    out = subprocess.run(["swarmvm", "gen", str(b.ROOT / EXAMPLE), "--target", "python", "-o", str(tmp_path),
                          "--sct-header", "sct.h"], capture_output=True, text=True)
    assert out.returncode == 2 and "--sct-header is for the C targets" in out.stderr


@pytest.mark.parametrize("target, folder", [("kilobot", ""), ("capbot", "src/")])
def test_sct_header_goes_beside_the_tables(target, folder, tmp_path):
    """On every C target the header lands beside <name>_tables.h and includes it."""
    out = subprocess.run(["swarmvm", "gen", str(b.ROOT / EXAMPLE), "--target", target, "-o", str(tmp_path),
                          "--sct-header", "sct_work_and_charge.h"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    header = (tmp_path / folder / "sct_work_and_charge.h").read_text()
    assert '#include "energy_worker_tables.h"' in header and (tmp_path / folder / "energy_worker_tables.h").is_file()


def test_the_published_form_readme_commands_run():
    """benchmarks/published_form/README.md's build commands, as written, from the checkout."""
    text = (b.PUBLISHED_FORM / "README.md").read_text()
    [block] = re.findall(r"^```sh\n(.*?)^```", text, re.M | re.S)
    run = subprocess.run(["bash", "-c", "set -e -o pipefail\n" + block], cwd=b.ROOT, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert (b.ROOT / "build" / "published_form" / "published_vm.o").is_file()
