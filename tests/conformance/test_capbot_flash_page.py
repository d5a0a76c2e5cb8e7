"""One CapBot VM binary runs any supervisor from the control-logic flash page (QEMU mps2-an386).

The harness ELF (firmware/capbot/page_harness/) is built ONCE, with the page limits of
firmware/capbot/page_limits.flags and the example energy_worker compiled in as the fallback.
Each QEMU run writes a supervisor's image into the page (0x000F3000) and its conformance
batch (scripts + runs, the "SVMC" blob of page_harness.c) at 0x00200000 with QEMU's generic
loader; every trace must equal the Python reference. A damaged, wrong-version, over-limits or
missing image must be refused with its swarmvm.h code, and then the compiled-in energy_worker
must run (its own batch's reference traces). The make rules are checked too: the Intel HEX of
a page loads at the right address, and the application binary logic-vm.elf runs the page's
model, or says why not and runs its compiled-in one."""

import struct
import subprocess

import pytest

from conformance import c_harness, qemu_harness
from conformance._c_compare import mismatches
from targets.capbot.app_environment import environment_script
from conformance.cases import SUPERVISORS, batch
from swarmvm.compiler.runtime_files import image_format, python_vm
from checkout import ROOT

pytestmark = pytest.mark.emulator   # runs simavr or QEMU

PAGE = 0x000F3000               # mps2_an386.ld: memory region SVM_LOGIC
CASES_BLOB = 0x00200000         # page_harness.c: CASES_BLOB
PAGE_HARNESS = qemu_harness.CAPBOT / "page_harness"
PAGE_LIMITS = qemu_harness.CAPBOT / "page_limits.flags"
EXAMPLE = ROOT / "examples" / "energy_worker" / "supervisor.yaml"
FALLBACK = next(p for p in SUPERVISORS if p.endswith("/energy_worker.yaml"))
SVM_ERR_LENGTH, SVM_ERR_VERSION, SVM_ERR_CRC, SVM_ERR_LIMITS = 1, 3, 4, 6
vm = python_vm()
FORMAT = image_format()


@pytest.fixture(scope="module")
def elf(tmp_path_factory):
    """The one harness binary: the generated energy_worker application's src/ (tables,
    controller, VM, swarmvm_logic_page.c) minus its Zephyr main, the compiled-in image as the fallback."""
    root = tmp_path_factory.mktemp("capbot_page")
    app = root / "gen"
    subprocess.run(["swarmvm", "gen", str(EXAMPLE), "--target", "capbot", "-o", str(app), "--name", "energy_worker"],
                   check=True, capture_output=True, text=True)
    sources = [s for s in sorted((app / "src").glob("*.c")) if s.name != "main.c"]
    sources += [PAGE_HARNESS / "page_harness.c", qemu_harness.CAPBOT / "capbot_qemu.c", c_harness.HARNESS / "svm_harness.c"]
    defines = ["@%s" % PAGE_LIMITS, "-DSVM_APP=energy_worker", '-DSVM_APP_HEADER="energy_worker_tables.h"']
    includes = [PAGE_HARNESS, app / "src", qemu_harness.CAPBOT, c_harness.HARNESS]
    return qemu_harness.compile_m4(sources, root / "page_harness.elf", defines, includes)


def cases_blob(b):
    """The batch's scripts and runs in page_harness.c's blob format (rows and runs encoded as
    in c_harness.cases_header)."""
    mask_bytes = b.image[13]
    rows = b"".join(sum(1 << e for e in row).to_bytes(mask_bytes, "little") for s in b.scripts for row in s)
    runs = b"".join(bytes([c_harness.options_byte(r), r.script]) + r.seed.to_bytes(4, "little") for r in b.runs)
    return b"SVMC" + struct.pack("<HHB3xI", len(b.scripts[0]), len(b.runs), mask_bytes, len(rows)) + rows + runs


def run_page(elf, tmp_path, b, page=None, page_file=None):
    """QEMU with ``page`` (image bytes, raw at PAGE) or ``page_file`` (Intel HEX) and the batch
    of ``b``; returns (exit status, @page code, traces, info)."""
    blob = tmp_path / ("%s.cases" % b.name)
    blob.write_bytes(cases_blob(b))
    loaders = ["-device", "loader,file=%s,addr=0x%x,force-raw=on" % (blob, CASES_BLOB)]
    if page is not None:
        page_file = tmp_path / "page.svm"
        page_file.write_bytes(page)
        loaders += ["-device", "loader,file=%s,addr=0x%x,force-raw=on" % (page_file, PAGE)]
    elif page_file is not None:
        loaders += ["-device", "loader,file=%s" % page_file]
    status, stdout, _ = qemu_harness.run(elf, loaders)
    first, _, rest = stdout.partition("\n")
    assert first.startswith("@page "), stdout[:200]
    traces, info = c_harness.parse(rest)
    return status, int(first.split()[1]), traces, info


def with_crc(image):
    body = bytes(image[:-2])
    return body + struct.pack("<H", vm.crc16(body))


def over_limits_image(events=33):
    """A valid image with one more event than page_limits.flags allows (1 supervisor, 1 state)."""
    m = (events + 7) // 8
    return FORMAT.assemble(events, 1, 1, 0, 1, {
        "controllable": bytes(m), "public": bytes(m),
        "supervisors": bytes(m) + FORMAT.SUPERVISOR_RECORD.pack(0, 1, 0),
        "states": bytes(m) + FORMAT.STATE_RECORD.pack(0), "targets": b""})


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_page_image_runs_in_the_one_binary(elf, tmp_path, path):
    b = batch(path)
    status, page, traces, info = run_page(elf, tmp_path, b, page=b.image)
    assert (status, page) == (0, 0)
    assert mismatches(b, traces, info, (0,)) == []


def damaged(image):
    bad = bytearray(image)
    bad[len(bad) // 2] ^= 0x01
    return bytes(bad)


def wrong_version(image):
    return with_crc(image[:4] + bytes([image[4] + 1]) + image[5:])


@pytest.mark.parametrize("make_page, code", [
    (lambda: damaged(batch(SUPERVISORS[-1]).image), SVM_ERR_CRC),
    (lambda: wrong_version(batch(SUPERVISORS[-1]).image), SVM_ERR_VERSION),
    (over_limits_image, SVM_ERR_LIMITS),
    (lambda: None, SVM_ERR_LENGTH),          # nothing written: QEMU's page reads 0 (length 0)
], ids=["bad-crc", "wrong-version", "over-limits", "empty"])
def test_refused_page_reports_its_code_and_the_fallback_runs(elf, tmp_path, make_page, code):
    page = make_page()
    if code == SVM_ERR_LIMITS:
        assert vm.Image.parse(page).num_events == 33, "the over-limits image must itself be valid"
    fallback = batch(FALLBACK)
    status, got, traces, info = run_page(elf, tmp_path, fallback, page=page)
    assert (status, got) == (0, code)
    assert mismatches(fallback, traces, info, (0,)) == []


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """mk/capbot.mk's page tools: the VM binary logic-vm.elf and uav's page as Intel HEX."""
    build = tmp_path_factory.mktemp("capbot_make")
    targets = [build / "capbot" / "logic-vm.elf", build / "capbot" / "uav-logic.hex"]
    subprocess.run(["make", "-s", "BUILD=%s" % build, *map(str, targets)], cwd=ROOT, check=True, capture_output=True)
    return targets


def test_logic_hex_rule_writes_the_page(elf, tmp_path, made):
    """`make build/capbot/<name>-logic.hex` puts the image at the page address: QEMU loads the
    Intel HEX as is (no address given) and the binary runs that image."""
    b = batch(next(p for p in SUPERVISORS if p.endswith("/uav.yaml")))
    status, page, traces, info = run_page(elf, tmp_path, b, page_file=made[1])
    assert (status, page) == (0, 0)
    assert mismatches(b, traces, info, (0,)) == []


PAGES = {   # what the page holds -> (model that runs, stderr of logic-vm.elf)
    "uav-page": ("uav", "logic page: running its image\n"),
    "unloaded-page": ("energy_worker", "logic page: blank (never written), running the compiled-in energy_worker\n"),
    "erased-page": ("energy_worker", "logic page: blank (never written), running the compiled-in energy_worker\n"),
    "damaged-page": ("energy_worker", "logic page: not a valid image, refused (swarmvm error %d), running the "
                                      "compiled-in energy_worker\n" % SVM_ERR_CRC),
}


@pytest.mark.parametrize("page", sorted(PAGES))
def test_application_runs_the_page_or_its_compiled_in_logic(made, tmp_path, page):
    """logic-vm.elf (energy_worker's application, page limits) runs uav from the page, with the
    environment app_qemu.c plays; otherwise it runs energy_worker and says why: a page never
    written (QEMU's zeros, erased flash's 0xFF) plainly as blank, a damaged one as refused with its code."""
    vm_elf, hex_file = made
    model, message = PAGES[page]
    image = vm.Image.parse(batch(next(p for p in SUPERVISORS if p.endswith("/%s.yaml" % model))).image)
    loader = {"uav-page": ["-device", "loader,file=%s" % hex_file], "unloaded-page": []}.get(page)
    if loader is None:
        raw = tmp_path / "page.bin"
        uav = batch(next(p for p in SUPERVISORS if p.endswith("/uav.yaml"))).image
        raw.write_bytes(b"\xff" * 4096 if page == "erased-page" else damaged(uav))
        loader = ["-device", "loader,file=%s,addr=0x%x,force-raw=on" % (raw, PAGE)]
    status, stdout, stderr = qemu_harness.run(vm_elf, loader, timeout=30)
    assert status == 0
    assert stdout.splitlines() == vm.replay(vm.VM(image), environment_script(image))
    assert stderr == message
