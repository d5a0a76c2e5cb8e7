"""Build and run the C conformance harness on a Cortex-M4F in QEMU (``mps2-an386``).

The batch header, the compile-time limits and the output parser are the common ones of
``c_harness``; this module adds the bare-metal build (``firmware/capbot/``: start-up code,
linker script, semihosting platform, flags in ``m4.flags``) and the QEMU run."""

import subprocess
import tempfile
from pathlib import Path

from conformance import c_harness
from checkout import FIRMWARE

CAPBOT = FIRMWARE / "capbot"
FLAGS = "@%s" % (CAPBOT / "m4.flags")
LINKER_SCRIPT = CAPBOT / "mps2_an386.ld"
STARTUP = CAPBOT / "startup.c"
QEMU = ["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
        "-semihosting-config", "enable=on,target=native"]
ICOUNT = ["-icount", "shift=10"]     # platform_qemu.c converts SysTick ticks with this shift
QEMU_TIMEOUT = 60


def compile_m4(sources, elf, defines=(), includes=()):
    """Link a bare-metal Cortex-M4F ELF for QEMU from C sources."""
    command = ["arm-none-eabi-gcc", FLAGS, *defines, *("-I%s" % d for d in includes),
               "-T", str(LINKER_SCRIPT), *map(str, [STARTUP, *sources]), "-o", str(elf)]
    subprocess.run(command, check=True, capture_output=True, text=True)
    return elf


def build_qemu(batch, outdir, cycles=False, root=None, extra=(), loaded=c_harness.LOADED_FULL):
    """One harness ELF for the batch, image both compiled in and loaded (RAM is plentiful).
    ``root``: another version's runtime and harness (c_harness.tree), e.g. the baseline's;
    ``extra``: more compiler flags (-D...); ``loaded``: the loaded pass (c_harness.LOADED_*)."""
    outdir = Path(outdir)
    c_harness._write_header(batch, outdir, loaded)
    runtime, harness = c_harness.tree(root)
    platform = (Path(root) / "firmware" / "capbot" if root is not None else CAPBOT) / "platform_qemu.c"
    sources = [runtime / "swarmvm.c", harness / "svm_harness.c", platform]
    defines = [*c_harness.limits(batch), *(["-DSVM_HARNESS_CYCLES"] if cycles else []), *extra]
    return compile_m4(sources, outdir / ("harness_%s.elf" % batch.name), defines, [outdir, runtime, harness])


def run(elf, extra=(), icount=False, timeout=QEMU_TIMEOUT):
    """(exit status, stdout, stderr) of one QEMU run of a bare-metal ELF, ``extra`` options added.

    QEMU's output goes to files, not pipes: semihosting writes to a pipe that is full on a busy
    machine fail with EAGAIN and the output is lost."""
    command = ["timeout", str(timeout), *QEMU, *(ICOUNT if icount else []), "-kernel", str(elf), *extra]
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        status = subprocess.run(command, stdout=out, stderr=err, stdin=subprocess.DEVNULL).returncode
        out.seek(0)
        err.seek(0)
        return status, out.read(), err.read()


def run_qemu(elf, icount=False, timeout=QEMU_TIMEOUT):
    """(exit status, stdout) of one QEMU run of a bare-metal ELF."""
    status, stdout, _ = run(elf, icount=icount, timeout=timeout)
    return status, stdout
