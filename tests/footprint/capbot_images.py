"""CapBot images for the stack and cycles tests: the bare-metal energy_worker of mk/capbot.mk
rebuilt in another build folder, with its atWork check given a big local array (a deeper
step), a busy-wait (a slower step), or its stack painted at start (startup.c, SVM_STACK_PAINT),
and how the tests declare its indirect calls (mk/capbot.mk's CAPBOT_INDIRECT)."""

import re
import shutil
from pathlib import Path

from checkout import ROOT
from target_builds import image_path, make_images

DEEPER_ARRAY = 300
DEEPER = """
    volatile unsigned char deeper[%d];     /* tests/footprint: a callback with a big local array */
    deeper[(unsigned)cb_measure_vcap() %% sizeof deeper] = 1;
    return 0;
""" % DEEPER_ARRAY
SLOWER_LOOPS = 50
SLOWER = """
    volatile unsigned spin;                /* tests/footprint: a callback that busy-waits */
    for (spin = 0; spin < %du; spin++) {
    }
    return 0;
""" % SLOWER_LOOPS
CHECK = "unsigned char energy_worker_check_atWork(void)\n{\n"


def capbot_indirect() -> list[str]:
    """The --indirect arguments mk/capbot.mk declares for its images (CAPBOT_INDIRECT)."""
    text = (ROOT / "mk" / "capbot.mk").read_text().replace("\\\n", " ")
    declared = re.search(r"^CAPBOT_INDIRECT := (.*)$", text, re.M).group(1)
    return declared.split()


def example(build: Path) -> Path:
    return image_path(build, "capbot", "energy_worker")


def rebuilt(build: Path, folder: Path, check_body: str | None = None, cflags: str = "") -> Path:
    """The CapBot energy_worker.elf of ``build`` built again in the build folder ``folder`` by
    mk/capbot.mk, its controller's atWork check replaced by ``check_body`` when given."""
    shutil.copytree(build / "capbot" / "gen" / "energy_worker", folder / "capbot" / "gen" / "energy_worker")
    if check_body is not None:
        controller = folder / "capbot" / "gen" / "energy_worker" / "src" / "energy_worker_controller.c"
        text = controller.read_text()
        body = text.index(CHECK) + len(CHECK)
        controller.write_text(text[:body] + check_body + text[text.index("}\n", body):])
    make_images(folder, [example(folder)], "CAPBOT_CFLAGS=%s" % cflags)
    return example(folder)
