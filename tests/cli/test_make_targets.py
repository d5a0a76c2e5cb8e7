"""Every per-area make target sets up first (issue 27, point 9): on a fresh clone, with no venv
yet, `make firmware` and the like ran `.venv/bin/python` and failed with Error 127. `make -n`
with a venv that does not exist shows what each would run: scripts/setup.sh, before anything."""

import os
import re
import subprocess

import pytest

from checkout import ROOT

# Every phony rule of mk/*.mk, and the Makefile's per-area gen (argos-for-test runs inside
# `make test`, after its set-up).
MK = "\n".join(p.read_text() for p in sorted((ROOT / "mk").glob("*.mk")))
TARGETS = sorted({t for line in re.findall(r"^\.PHONY:(.*)$", MK, re.M) for t in line.split()} - {"argos-for-test"}
                 | {"gen"})


def first_command(target: str, tmp_path) -> str:
    """The first command ``make -n TARGET`` shows, as a user's own make runs it (not as a sub-make
    of `make test`, whose MAKEFLAGS and MAKELEVEL the suite inherits)."""
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS", "MAKEFILES")}
    dry = subprocess.run(["make", "-n", target, "VENV=%s" % (tmp_path / "no-venv"), "BUILD=%s" % (tmp_path / "build")],
                         cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
    return next((line for line in dry.stdout.splitlines() if line.strip()), dry.stderr)


@pytest.mark.parametrize("target", TARGETS)
def test_a_per_area_target_sets_up_first(target, tmp_path):
    assert "scripts/setup.sh" in first_command(target, tmp_path)
