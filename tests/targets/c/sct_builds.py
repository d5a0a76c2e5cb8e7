"""Builds of one driver (tests/targets/c/sct_driver.c) against the VMs the Nadzoru C API runs on:
the published-form VM (benchmarks/published_form/published_vm.c) with published-form tables
(tests/nadzoru_c_form.py, through benchmarks/published_form/tables.py), the real published
CapBot file, and swarmvm's C API (gen --target c, runtime_c) in exact or canonical mode. Each
build is a host executable printing one log line per step; tests/targets/c/test_sct_exact_c.py
compares the logs."""

import importlib.util
import re
import subprocess
from pathlib import Path

from checkout import ROOT
from swarmvm.api import generate_target

HERE = Path(__file__).resolve().parent
DRIVER = HERE / "sct_driver.c"
PUBLISHED_FORM = ROOT / "benchmarks" / "published_form"
PUBLISHED_VM = PUBLISHED_FORM / "published_vm.c"
RUNTIME_C = ROOT / "runtime_c"
REFERENCE = ROOT.parent / "shared" / "reference" / "freebot-capbot-sct" / "lib" / "sct"   # the published CapBot VM (MIT)
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wconversion", "-Werror", "-pedantic"]
CC = ["gcc", "-O1"]


def _tables_module():
    """benchmarks/published_form/tables.py, the benchmark's writer of the published form."""
    spec = importlib.util.spec_from_file_location("published_form_tables", PUBLISHED_FORM / "tables.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def compile_c(command: list[str], cwd: Path) -> None:
    """Run a compiler; AssertionError with its messages when it fails or warns."""
    out = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    assert (out.returncode, out.stderr) == (0, ""), " ".join(map(str, command)) + "\n" + out.stderr


def published_form(supervisor: Path, folder: Path, defines: tuple[str, ...] = ()) -> Path:
    """The driver on the published-form VM with ``supervisor``'s published-form tables."""
    folder.mkdir(parents=True, exist_ok=True)
    _tables_module().write(supervisor, folder)
    binary = folder / "published"
    compile_c([*CC, *STRICT, "-I%s" % folder, '-DSCT_HEADER="model.h"', '-DSCT_TABLES="model_tables.c"', *defines,
               str(DRIVER), str(PUBLISHED_VM), "-o", str(binary)], folder)
    return binary


def real_published(folder: Path, vm: Path | None = None) -> Path:
    """The driver on the published CapBot work_and_charge file itself (``vm`` None), or on the
    published-form VM given that file's tables (``vm``: published_vm.c)."""
    folder.mkdir(parents=True, exist_ok=True)
    source = REFERENCE / "src" / "sct_work_and_charge.c"
    binary = folder / ("real" if vm is None else "published_form")
    common = [*CC, "-I%s" % (REFERENCE / "inc"), "-I%s" % folder, '-DSCT_HEADER="sct_work_and_charge.h"']
    if vm is None:      # the published file as it is, warnings and all: it is not ours to fix
        compile_c([*common, "-w", str(DRIVER), str(source), "-o", str(binary)], folder)
        return binary
    text = source.read_text()
    start = text.index("#if FN_SUP")
    (folder / "wc_tables.c").write_text('#include "sct_work_and_charge.h"\n' + text[start:text.index("#endif", start)]
                                        + "#endif\n")
    compile_c([*common, "-Wall", "-Wextra", "-Werror", '-DSCT_TABLES="wc_tables.c"', str(DRIVER), str(vm),
               "-o", str(binary)], folder)
    return binary


def limits(folder: Path) -> list[str]:
    """The model's exact -DSVM_MAX_* flags, as the generated Makefile gives them."""
    return re.findall(r"-DSVM_MAX_[A-Z_]+=[0-9]+", (folder / "Makefile").read_text())


def swarmvm(supervisor: Path, folder: Path, exact: bool, defines: tuple[str, ...] = (),
            sct_header: str | None = None, extra: tuple[Path, ...] = ()) -> Path:
    """The driver on swarmvm's C API: gen --target c's tables (the tables file alone: no
    controller, no dispatch) with swarmvm.c and swarmvm_sct.c, SVM_SCT_EXACT=1 or 0."""
    generate_target([str(supervisor)], "c", str(folder), name="model", sct_header=sct_header)
    binary = folder / ("exact" if exact else "canonical")
    header = sct_header or "model_tables.h"
    compile_c([*CC, *STRICT, *limits(folder), "-DSVM_SCT_EXACT=%d" % exact, "-DDRIVER_SCT_STATE",
               '-DSCT_HEADER="%s"' % header, "-I%s" % folder, *defines, str(DRIVER),
               *(str(folder / f) for f in ("model_tables.c", "swarmvm.c", "swarmvm_sct.c")), *map(str, extra),
               "-o", str(binary)], folder)
    return binary


def run(binary: Path, steps: int, seed: int) -> list[str]:
    out = subprocess.run([str(binary), str(steps), str(seed)], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stdout[-500:] + out.stderr
    return out.stdout.splitlines()
