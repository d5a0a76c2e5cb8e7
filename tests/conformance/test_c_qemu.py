"""Conformance of the C VM on a Cortex-M4F in QEMU (mps2-an386, bare metal, semihosting).

The common C harness (firmware/harness/) with the platform firmware/capbot/platform_qemu.c:
one firmware per corpus supervisor runs every run of its batch twice, with the image compiled
in (flash) and with a RAM copy loaded at run time, and every trace must equal the Python
reference byte for byte. main's return value is QEMU's exit status."""

import pytest

from conformance import c_harness, qemu_harness
from conformance._c_compare import mismatches
from conformance.cases import SUPERVISORS, batch

pytestmark = pytest.mark.emulator   # runs simavr or QEMU


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.rsplit("/", 1)[-1][:-5])
def test_qemu_trace_equals_reference(path, tmp_path):
    b = batch(path)
    elf = qemu_harness.build_qemu(b, tmp_path)
    status, output = qemu_harness.run_qemu(elf)
    traces, info = c_harness.parse(output)
    assert status == 0, "QEMU exit status %d (the harness returns 0 when the image loaded)" % status
    assert mismatches(b, traces, info, (0, 1)) == []


def test_qemu_exit_status_is_mains_return_value(tmp_path):
    """The start-up self-test returns 42 only when .data was copied, .bss zeroed and the FPU
    enabled; QEMU must hand that value back (a fault would give 127, a hang the timeout's 124)."""
    elf = qemu_harness.compile_m4([qemu_harness.CAPBOT / "selftest.c"], tmp_path / "selftest.elf")
    status, output = qemu_harness.run_qemu(elf, timeout=20)
    assert (status, output) == (42, "capbot selftest: data ok, bss ok, fpu ok\n")
