"""Build and run the C conformance harness on a Cortex-M4F in QEMU (``mps2-an386``).

The batch header, the compile-time limits and the output parser are the common ones of
``c_harness``; this module adds the bare-metal build (``firmware/capbot/``: start-up code,
linker script, semihosting platform, flags in ``m4.flags``) and the QEMU run."""

import subprocess
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


def build_qemu(batch, outdir, cycles=False):
    """One harness ELF for the batch, image both compiled in and loaded (RAM is plentiful)."""
    outdir = Path(outdir)
    c_harness._write_header(batch, outdir, c_harness.LOADED_FULL)
    sources = c_harness.CORE_SOURCES + c_harness.HARNESS_SOURCES + [CAPBOT / "platform_qemu.c"]
    defines = [*c_harness.limits(batch), *(["-DSVM_HARNESS_CYCLES"] if cycles else [])]
    includes = [outdir, c_harness.RUNTIME_C, c_harness.HARNESS]
    return compile_m4(sources, outdir / ("harness_%s.elf" % batch.name), defines, includes)


def run_qemu(elf, icount=False, timeout=QEMU_TIMEOUT):
    """(exit status, stdout) of one QEMU run of a bare-metal ELF."""
    command = QEMU + (ICOUNT if icount else []) + ["-kernel", str(elf)]
    proc = subprocess.run(["timeout", str(timeout)] + command, capture_output=True, text=True)
    return proc.returncode, proc.stdout
