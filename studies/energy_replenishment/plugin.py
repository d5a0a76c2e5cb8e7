"""The study's ARGoS plugin, built once per version of its sources and cached: the three
supervisors generated with ``swarmvm gen --target argos`` (their user files are this package's
controllers in argos/), the loop functions, one CMake build against real ARGoS.

The cache key hashes every input (the C++ sources, the supervisors, the generated files, the
ARGoS prefix), so editing any of them rebuilds; concurrent callers (the processes of a sweep)
wait on a lock and a finished build is renamed into place, so a half-built plugin is never used.
A build takes about ten seconds: stderr says so, names the log that keeps its whole output, and
reports make's per cent as it goes."""

from __future__ import annotations

import fcntl
import glob
import hashlib
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

from swarmvm import api
from swarmvm.boundary import terminal

PACKAGE = Path(__file__).resolve().parent
SOURCES = PACKAGE / "argos"
SUPERVISORS = PACKAGE / "supervisors"
NAMES = ("energy_worker", "energy_worker_mc", "energy_charger")
LIBRARY = "libenergy_study"
PERCENT = re.compile(r"\[ *(\d+)%\]")   # make's progress, at the start of its lines


class BuildError(RuntimeError):
    """ARGoS is missing or the plugin does not build; the message says which."""


def find_argos() -> Path:
    """The ARGoS install prefix (holding bin/argos3), looked for as scripts/argos.sh does:
    ARGOS_PREFIX, argos3 on PATH, the usual prefixes, then the cache where argos.sh builds it."""
    candidates = []
    if os.environ.get("ARGOS_PREFIX"):
        candidates.append(Path(os.environ["ARGOS_PREFIX"]))
    on_path = shutil.which("argos3")
    if on_path:
        candidates.append(Path(on_path).resolve().parent.parent)
    candidates += [Path(p) for p in ("/usr/local", "/usr", "/opt", "/opt/local")]
    candidates += [Path(p) for p in sorted(glob.glob(str(cache_root() / "argos3-*")))]
    for prefix in candidates:
        if (prefix / "bin" / "argos3").is_file() and (prefix / "include" / "argos3").is_dir():
            return prefix
    raise BuildError("ARGoS 3 not found: install it (its source builds with cmake and make install), or set "
                     "ARGOS_PREFIX to the folder holding its bin/argos3")


def cache_root() -> Path:
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "swarmvm"


def _generate(folder: Path) -> None:
    """Each supervisor's ARGoS project, with this study's controller files as the user files."""
    for name in NAMES:
        target = folder / name
        target.mkdir(parents=True)
        for suffix in ("_controller.h", "_controller.cpp"):
            shutil.copy(SOURCES / (name + suffix), target / (name + suffix))
        generated = api.generate_target([str(SUPERVISORS / (name + ".yaml"))], "argos", str(target), name=name)
        if generated.drifts:
            raise BuildError("; ".join(d.message() for d in generated.drifts))
    for path in SOURCES.iterdir():
        if not path.name.startswith(NAMES) or not path.name.endswith(("_controller.h", "_controller.cpp")):
            shutil.copy(path, folder / path.name)


def _key(folder: Path, prefix: Path, cxx_flags: str) -> str:
    digest = hashlib.sha256(("%s\0%s" % (prefix, cxx_flags)).encode())
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        digest.update(str(path.relative_to(folder)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


def run_logged(command: list[str], log: Path, what: str, every: int = 25) -> bool:
    """Runs ``command`` with its whole output appended to ``log``; on stderr, ``what`` and make's
    per cent each time it has gone ``every`` points further, so that a wait says how far it is
    without the build log. True when the command succeeded."""
    shown = -every
    with open(log, "a") as out, subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                                 text=True, errors="replace") as process:
        assert process.stdout is not None
        for text in process.stdout:
            out.write(text)
            done = PERCENT.match(text)
            if done and (int(done.group(1)) >= shown + every or int(done.group(1)) == 100 > shown):
                shown = int(done.group(1))
                terminal.note("%s: %d%%" % (what, shown))
    return process.returncode == 0


def build(cache: Path | None = None, cxx_flags: str = "") -> Path:
    """The plugin library's path without its suffix (as ARGoS's ``library=`` takes it), built
    if this version of its sources has not been built yet (``cxx_flags``: extra compiler flags,
    part of the key; the tests build with -Werror)."""
    prefix = find_argos()
    root = Path(cache) if cache else cache_root() / "energy-plugin"
    root.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=root, prefix=".src-") as temp:
        sources = Path(temp) / "src"
        _generate(sources)
        key = _key(sources, prefix, cxx_flags)
        done = root / key
        library = done / "build" / LIBRARY
        if (done / "build" / (LIBRARY + ".so")).is_file():
            return library
        with open(root / ".lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if (done / "build" / (LIBRARY + ".so")).is_file():
                return library
            log = root / "build.log"
            log.write_text("")
            terminal.note("building the energy study's ARGoS plugin, once for these sources (about 10 s); "
                          "full output: %s" % log)
            for command, what in ((["cmake", "-S", str(sources), "-B", str(sources / "build"), "-DCMAKE_BUILD_TYPE=Release",
                                    "-DARGOS_PREFIX=%s" % prefix, "-DCMAKE_CXX_FLAGS=%s" % cxx_flags], "configuring"),
                                  (["cmake", "--build", str(sources / "build"), "-j", "2"], "compiling the plugin")):
                if not run_logged(command, log, what):
                    raise BuildError("the energy plugin does not build:\n" + log.read_text()[-4000:])
            shutil.rmtree(done, ignore_errors=True)
            os.replace(sources, done)
    return library
