"""One trial of the energy-replenishment study in real ARGoS: the experiment file written from
the trial's :class:`Params`, ``argos3`` run headless on it, the loop functions' JSON result read
back and measured against the bound."""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

from swarmvm.boundary.output import write_outputs

from . import plugin
from .experiment import experiment, robot_kinds
from .params import Params


class TrialError(RuntimeError):
    """ARGoS failed on a trial; the message carries its error output."""


def run(p: Params, library: Path | None = None, trace: Path | None = None, baseline: bool = False,
        vm_traces: Path | None = None) -> dict:
    """The trial's result: the loop functions' totals, the bound and the wall time. ``library``:
    a plugin already built (:func:`plugin.build`); ``trace``: write the per-step CSV there;
    ``baseline``: the same robots with an empty controller (benchmarks/energy_study.py);
    ``vm_traces``: write each robot's VM trace (canonical lines, docs/conformance.md) into that
    folder as ``<supervisor>/<robot>.trace``, which ``swarmvm inspect`` reads (docs/inspect.md).

    A relative ``trace`` is the caller's: ARGoS runs in a temporary folder, removed after the
    trial, where a relative path would have written it (and lost it). A trace asked for and not
    written is a TrialError, not a trial that seems to have run."""
    trace = Path(trace).absolute() if trace else None
    library = library or plugin.build()
    prefix = plugin.find_argos()
    env = dict(os.environ, LD_LIBRARY_PATH=os.pathsep.join(filter(None, [str(prefix / "lib" / "argos3"),
                                                                          os.environ.get("LD_LIBRARY_PATH")])),
               ARGOS_PLUGIN_PATH=str(prefix / "lib" / "argos3"))
    with tempfile.TemporaryDirectory(prefix="swarmvm-energy-") as folder:
        result = Path(folder) / "result.json"
        config = Path(folder) / "trial.argos"
        log = Path(folder) / "log.txt"
        config.write_text(experiment(p, library, result, trace, baseline, vm_traces is not None))
        start = time.perf_counter()
        done = subprocess.run([str(prefix / "bin" / "argos3"), "-n", "-c", str(config), "-l", str(log),
                               "-e", str(Path(folder) / "err.txt")], cwd=folder, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        seconds = time.perf_counter() - start
        if done.returncode != 0 or not result.is_file():
            errors = (Path(folder) / "err.txt").read_text() if (Path(folder) / "err.txt").is_file() else ""
            raise TrialError("argos3 failed (status %d): %s" % (done.returncode, (errors + done.stderr).strip()[-2000:]))
        totals = json.loads(result.read_text())
        if vm_traces is not None:
            write_outputs(vm_traces, vm_trace_files(log.read_text(), robot_kinds(p)), option="--vm-traces")
    if trace and not trace.is_file():
        raise TrialError("argos3 wrote no trace to %s (is its folder there and writable?)" % trace)
    bound = p.bound()
    if bound is None:
        totals.update(bound_work=None, bound_efficiency=None, work_of_bound=None)
    else:
        totals.update(bound_work=bound.work, bound_efficiency=bound.efficiency, work_of_bound=totals["work"] / bound.work)
    totals.update(seconds=seconds)
    return totals


def vm_trace_files(log: str, kinds: dict[str, str]) -> dict[str, tuple[bytes, bool]]:
    """The robots' ``trace ID: LINE`` lines of an ARGoS log as trace files, ``<kind>/<ID>.trace``
    (``kinds``: robot id prefix -> the supervisor its controller runs), for write_outputs."""
    lines: dict[str, list[str]] = {}
    for line in log.splitlines():
        if line.startswith("trace "):
            robot, rest = line[len("trace "):].split(" ", 1)
            robot = robot.rstrip(":")
            lines.setdefault("%s/%s.trace" % (kinds[robot.rstrip("0123456789")], robot), []).append(rest + "\n")
    return {path: ("".join(rows).encode(), False) for path, rows in sorted(lines.items())}
