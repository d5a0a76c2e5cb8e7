"""The real images the footprint tests measure, and how the tests run the command on them:
the CapBot and Kilobot applications of two corpus supervisors (mk/capbot.mk, mk/kilobot.mk),
a Kilobot energy_worker whose controller grew (a table in flash, a buffer in RAM), for
budgets and deltas to catch, one whose callback needs a deeper stack and one whose callback
busy-waits (a slower step). conftest.py builds them once per session."""

import shutil
import subprocess
import sys
from pathlib import Path

from checkout import EXAMPLE, ROOT
from swarmvm import api
from swarmvm.targets.kilobot import TARGET as KILOBOT_TARGET
from target_builds import image_path, make_images, measured_targets

NAMES = ("energy_worker", "network_worker")
BALLAST_FLASH, BALLAST_RAM = 600, 100
BALLAST = """
/* Ballast (tests/footprint): the controller grew by a table in flash and a buffer in RAM. */
#include <avr/pgmspace.h>
static const unsigned char ballast_flash[%d] PROGMEM = {1, 2, 3};
volatile unsigned char ballast_ram[%d];
__attribute__((constructor)) static void ballast(void) { ballast_ram[0] = pgm_read_byte(&ballast_flash[ballast_ram[1]]); }
""" % (BALLAST_FLASH, BALLAST_RAM)


def build_images(root: Path) -> None:
    """<root>/<target>/<name>.elf for every measured target (capbot, kilobot) and NAMES, by the
    project's make rules (their records' elf.make_rule)."""
    make_images(root, [image_path(root, target, name) for target in measured_targets() for name in NAMES])


def build_larger(root: Path, folder: Path) -> Path:
    """The Kilobot energy_worker.elf of `build_images(root)`, rebuilt by its generated Makefile
    in ``folder`` from a copy of its sources whose controller has the ballast appended."""
    shutil.copytree(root / "kilobot" / "gen" / "energy_worker", folder)
    (folder / "energy_worker.elf").unlink(missing_ok=True)
    with open(folder / "energy_worker_controller.c", "a") as controller:
        controller.write(BALLAST)
    return _make(folder)


DEEPER_ARRAY = 300
DEEPER = """
    volatile unsigned char deeper[%d];     /* tests/footprint: a callback with a big local array */
    deeper[kilo_ticks %% sizeof deeper] = 1;
    return deeper[0];
""" % DEEPER_ARRAY
# What the indirect calls of the Kilobot runtime (runtime_c/swarmvm_kilobot.c) and kilolib reach, as
# docs/footprint.md ("Stack") declares them: the Kilobot target's record, where footprint reads them.
KILOBOT_INDIRECT = KILOBOT_TARGET.elf.indirect


SLOWER_LOOPS = 50
SLOWER = """
    volatile unsigned char spin;           /* tests/footprint: a callback that busy-waits */
    for (spin = 0; spin < %d; spin++) {
    }
    return 0;
""" % SLOWER_LOOPS


def build_deeper(root: Path, folder: Path) -> Path:
    """The Kilobot energy_worker.elf of `build_images(root)`, rebuilt in ``folder`` with the
    check of atWork holding a DEEPER_ARRAY-byte local array: a VM step that needs more stack."""
    return _with_check(root, folder, DEEPER)


def build_slower(root: Path, folder: Path) -> Path:
    """The same, with the check of atWork busy-waiting SLOWER_LOOPS rounds: a slower VM step."""
    return _with_check(root, folder, SLOWER)


FLOAT = """
    static volatile float level = 1.5f;    /* tests/footprint: float arithmetic (avr-libc's __addsf3, __mulsf3) */
    return level * 3.0f + level > 4.0f;
"""
ESTIMATE = """
    static distance_measurement_t heard;   /* tests/footprint: kilolib's float estimate (built without .su) */
    return estimate_distance(&heard) > 50;
"""


def build_float(root: Path, folder: Path) -> Path:
    """The example with a check doing float arithmetic: avr-libc's assembly routines, one of
    them (``__addsf3``) without a size, in the VM step's call graph."""
    return _with_check(root, folder, FLOAT)


def build_estimate(root: Path, folder: Path) -> Path:
    """The example with a check calling kilolib's estimate_distance(): float code of a library
    built without -fstack-usage whose frame its code alone does not make certain."""
    return _with_check(root, folder, ESTIMATE)


def _with_check(root: Path, folder: Path, body_text: str) -> Path:
    """The example rebuilt in ``folder`` with ``body_text`` as the body of its atWork check."""
    shutil.copytree(root / "kilobot" / "gen" / "energy_worker", folder)
    for stale in ["energy_worker.elf", *(p.name for p in folder.glob("*.su"))]:
        (folder / stale).unlink(missing_ok=True)
    controller = folder / "energy_worker_controller.c"
    text = controller.read_text()
    check = "unsigned char energy_worker_check_atWork(void)\n{\n"
    body = text.index(check) + len(check)
    controller.write_text(text[:body] + body_text + text[text.index("}\n", body):])
    return _make(folder)


def _make(folder: Path) -> Path:
    kilolib = subprocess.run([sys.executable, str(ROOT / "firmware" / "kilobot" / "kilolib_build.py")], check=True,
                             capture_output=True, text=True).stdout.strip()
    subprocess.run(["make", "-s", "-C", str(folder), "energy_worker.elf", "KILOLIB=%s" % kilolib], check=True,
                   capture_output=True, text=True)
    return folder / "energy_worker.elf"


def elf(build: Path, target: str, name: str) -> Path:
    """The image of ``target`` and ``name``: for the Kilobot, where its generated Makefile built it,
    beside the .su files the worst-case stack needs (the copy make puts in build/kilobot/ has none,
    and an unknown stack fails the Kilobot's SRAM limit: fail closed)."""
    if target == "kilobot":
        return build / "kilobot" / "gen" / name / ("%s.elf" % name)
    return image_path(build, target, name)


def swarmvm_footprint(*args, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run(["swarmvm", "footprint", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def event_script(tmp_path: Path, lines) -> Path:
    """An event script of ``lines`` (one step each) for ``footprint --cycles``."""
    path = tmp_path / "events.txt"
    path.write_text("# swarmvm event script\n" + "".join(line + "\n" for line in lines))
    return path


def random_event_script(tmp_path: Path, steps: int = 12, seed: int = 3) -> Path:
    """A random event script of the bundled example's events."""
    path = tmp_path / "random.txt"
    path.write_text("".join(line + "\n" for line in api.script_lines([str(EXAMPLE)], steps=steps, seed=seed)))
    return path
