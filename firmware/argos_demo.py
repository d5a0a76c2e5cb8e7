"""`make argos-demo`: the bundled example's generated ARGoS project, built with its own
CMakeLists.txt against real ARGoS (scripts/argos.sh finds it or builds it once) and run there.

1. The generated .argos file as it is: six e-pucks in a walled arena, 300 control steps,
   headless; each robot prints its summary line. The generated checks are stubs that return
   false until the user reads the sensors, so only events that need no sensor can fire: each
   robot's count must be the Python VM's for a script in which no event occurs (for the bundled
   example, none), and the demo says so in words rather than leaving "0 events fired" to read
   like a failure.
2. The same experiment with a random event script (`swarmvm script`) standing in for those
   sensors (<report script=...>) and traces on: the summaries, then one verdict comparing every
   robot's trace with `swarmvm trace` for the script and the robot's VM seed (the experiment's
   random_seed XOR FNV-1a of its id); then the inspector's page of those traces, one lane per
   robot (`swarmvm inspect`, docs/inspect.md), whose path it prints.

Exit status 1 when ARGoS is missing or fails, or on any difference."""

import argparse
import os
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "targets" / "argos")]
os.environ["PATH"] = os.path.dirname(sys.executable) + os.pathsep + os.environ["PATH"]   # swarmvm beside python

from argos_project import (build, experiment, find_argos, generate, reference_trace,  # noqa: E402
                           robot_lines, robot_seed, run_argos, write_script)
from swarmvm import api  # noqa: E402


def run(project, experiment_file):
    """Runs one experiment; prints its summary lines; returns its LOG output."""
    start = time.perf_counter()
    status, log, err = run_argos(project, experiment_file)
    if status != 0:
        sys.exit("argos-demo: argos3 failed on %s:\n%s" % (experiment_file, err))
    summaries = robot_lines(log, "summary")
    print("   (%d e-pucks, %.2f s of wall time)" % (len(summaries), time.perf_counter() - start))
    for robot in sorted(summaries):
        print("%s: %s" % (robot, summaries[robot][0]))
    return log


def events_fired(summary):
    """K of a summary line "N steps, K events fired ..."."""
    return int(summary.split(" steps, ", 1)[1].split(" ", 1)[0])


def check_stub_run(project, log, steps, random_seed):
    """The run as generated, with every check a stub returning false: each robot fires what the
    Python VM fires when no event occurs, which the demo says plainly (0 for the bundled example)."""
    quiet = project.folder / "no_events.txt"
    quiet.write_text("-\n" * steps)
    fired = {robot: events_fired(lines[0]) for robot, lines in robot_lines(log, "summary").items()}
    expected = {robot: sum(len(line.split()[1].split(",")) for line in api.trace(
        [str(project.supervisor)], str(quiet), seed=robot_seed(random_seed, robot)) if line.split()[1] != "-")
        for robot in fired}
    if fired != expected:
        sys.exit("argos-demo: events fired with stub checks %s, the Python VM's %s" % (fired, expected))
    what = "no event fires" if not any(fired.values()) else "only the events that need no sensor fire"
    print("   as expected, %s: the generated checks (%s_controller.cpp) return false until they read the "
          "sensors, and the Python VM, given no event, fires the same" % (what, project.name))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--example", required=True, help="supervisor file of the bundled example")
    parser.add_argument("--name", default="energy_worker")
    parser.add_argument("--out", required=True, help="folder of the generated project")
    parser.add_argument("--script-seed", type=int, default=1)
    args = parser.parse_args()

    status, prefix, stderr = find_argos()
    if status != 0:
        sys.exit("argos-demo: %s" % stderr.strip())
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for old in out.iterdir():   # regenerate the kept files too: the demo shows what gen writes now
        if old.is_file():
            old.unlink()
    project = generate(args.example, out, args.name)
    build(project, "g++", "-DARGOS_PREFIX=%s" % prefix)

    generated = out / (args.name + ".argos")
    print("== %s as generated, in real ARGoS (%s):" % (generated, prefix))
    settings = ET.parse(generated).getroot().find("framework/experiment")
    steps = round(float(settings.get("length")) * int(settings.get("ticks_per_second")))
    random_seed = int(settings.get("random_seed"))
    check_stub_run(project, run(project, generated), steps, random_seed)
    script = write_script(project, steps, args.script_seed)
    print("== the same with an event script in place of the sensors (swarmvm script --steps %d --seed %d):"
          % (steps, args.script_seed))
    log = run(project, experiment(project, "scripted", report={"summary": "true", "trace": "true",
                                                               "script": script.name}))
    differ = [robot for robot, lines in sorted(robot_lines(log, "trace").items())
              if lines != reference_trace(project, script, robot_seed(random_seed, robot), None, robot)]
    if differ:
        sys.exit("argos-demo: the traces of %s differ from swarmvm trace (see %s)" % (", ".join(differ), out))
    print("every robot's trace identical to the Python VM (swarmvm trace --seed random_seed^FNV-1a(id))")
    traces = []
    for robot, lines in sorted(robot_lines(log, "trace").items()):
        traces.append(out / (robot + ".trace"))
        traces[-1].write_text("".join(line + "\n" for line in lines))
    page = api.inspect(args.example, [str(t) for t in traces], str(out / "inspect.html"), name=args.name)
    print("inspector page of the %d robots' traces: %s (docs/inspect.md)" % (len(traces), page.path))


if __name__ == "__main__":
    main()
