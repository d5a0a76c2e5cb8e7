"""Find the real kilolib, or build it once from its source archive into a cache.

Every Kilobot image the project builds (``make firmware``, the simavr tests, the swap demo)
links the real ``kilolib.a`` with kilolib's own compiler flags. Where it comes from, in order:

1. ``KILOLIB``: a kilolib checkout as a Kilobot user has one, the folder holding ``kilolib.h``
   and ``build/kilolib.a`` (``make`` in it builds that); taken as it is.
2. ``KILOLIB_SRC`` (default: ``../shared/vendor/kilolib-b95fdaf.tar.gz`` beside the checkout):
   the archive is unpacked and built (``make build/kilolib.a``, kilolib's own Makefile) into
   ``${XDG_CACHE_HOME:-~/.cache}/swarmvm/<archive name>/``, outside the checkout, once. The build
   runs in a temporary folder next to it that is renamed into place when complete, so builds
   running at the same time (parallel make, several pytest processes) never see half a library.

    python3 firmware/kilobot/kilolib_build.py     prints the kilolib folder (building it if need be)
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path
from typing import Callable

# No kilolib could be found or built (the message says why and how to get one): the package's
# error for a missing Kilobot tool, which the board raises too, and its cache folder.
from swarmvm.footprint.kilobot_board import KilobotToolMissing as KilolibMissing, cache_root

ROOT = Path(__file__).resolve().parent.parent.parent
DEFAULT_SOURCE = ROOT.parent / "shared" / "vendor" / "kilolib-b95fdaf.tar.gz"
LIBRARY = Path("build") / "kilolib.a"
HOW_TO_GET = ("set KILOLIB to a built kilolib checkout (https://github.com/acornejo/kilolib, `make` in it) "
              "or KILOLIB_SRC to its source archive, with avr-gcc installed (scripts/setup.sh)")


def is_kilolib(folder: Path) -> bool:
    """A usable kilolib folder: headers and the built library, as kilolib's Makefile leaves them."""
    return (folder / "kilolib.h").is_file() and (folder / "message.h").is_file() and (folder / LIBRARY).is_file()


def _archive_name(archive: Path) -> str:
    name = archive.name
    for suffix in (".tar.gz", ".tgz", ".tar.xz", ".tar"):
        if name.endswith(suffix):
            return name[: -len(suffix)]
    return name


def build(archive: Path, cache: Path) -> Path:
    """Unpack ``archive`` and build kilolib.a with its Makefile into ``cache/<archive name>``
    (once: an existing complete build is reused). Returns that folder."""
    target = cache / _archive_name(archive)
    if is_kilolib(target):
        return target
    if not archive.is_file():
        raise KilolibMissing("kilolib: no source archive at %s: %s" % (archive, HOW_TO_GET))
    if shutil.which("avr-gcc") is None:
        raise KilolibMissing("kilolib: avr-gcc not found: %s" % HOW_TO_GET)
    cache.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=".%s." % target.name, dir=cache))
    try:
        with tarfile.open(archive) as tar:
            tar.extractall(work, **({"filter": "data"} if hasattr(tarfile, "data_filter") else {}))
        tops = [p for p in work.iterdir() if p.is_dir()]
        source = tops[0] if len(tops) == 1 and not (work / "Makefile").exists() else work
        result = subprocess.run(["make", "-C", str(source), str(LIBRARY)], capture_output=True, text=True)
        if result.returncode != 0 or not is_kilolib(source):
            raise KilolibMissing("kilolib: building %s failed:\n%s" % (archive, result.stdout + result.stderr))
        try:
            source.rename(target)
        except OSError:
            if not is_kilolib(target):      # not another process's complete build: a real failure
                raise
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return target


def kilolib_dir() -> Path:
    """The kilolib folder to compile and link against (KILOLIB, else built from KILOLIB_SRC)."""
    given = os.environ.get("KILOLIB")
    if given:
        folder = Path(given).resolve()
        if not is_kilolib(folder):
            raise KilolibMissing("kilolib: KILOLIB=%s holds no kilolib.h, message.h and %s (run `make` in it)"
                                 % (given, LIBRARY))
        return folder
    return build(Path(os.environ.get("KILOLIB_SRC") or DEFAULT_SOURCE).resolve(), cache_root())


def print_path(find: Callable[[], Path]) -> int:
    """A script's main: print what ``find`` finds or builds, or why it cannot (status 1)."""
    try:
        print(find())
    except KilolibMissing as missing:
        print(missing, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(print_path(kilolib_dir))
