"""The inspector's page for a whole swarm's run (issue 38, point 2): 200 robots x 20,000 steps
(4 M robot-steps) of the bundled example, one page.

The traces are real canonical traces, each written by the reference VM (``swarmvm script`` and
``swarmvm trace``'s functions, one seed per robot; about a minute for the 200). Then measured:

- **written in**: the wall time of ``swarmvm inspect`` run as a user runs it (a new process, its
  start-up included), target 5 s; the page's bytes; the peak memory of that process (its maximum
  resident set), beside the traces' bytes.
- in Debian's headless Chromium (tests/inspector/browser.py): **loaded in**, navigation start to
  the load event (the page's script has run: the timeline and the drawings are drawn), target
  2 s; **a step drawn**: the page's handling of a key (its script, then the layout it forces),
  timed inside the page, for 200 steps with the Right key (mean and worst), a jump to the last
  step (End) and to the next robot (Down), target 16 ms (a frame at 60 Hz).

Prints one line per figure with its target and met / MISSED; ``--json FILE`` also writes them.
Without Chromium the browser's figures are left out, and a line says why."""

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "inspector"))

from browser import Browser, missing  # noqa: E402
from swarmvm import api  # noqa: E402
from figures import add_json_option, write_figures  # noqa: E402

SUPERVISOR = str(ROOT / "examples" / "energy_worker" / "supervisor.yaml")
ROBOTS, STEPS = 200, 20_000
WRITE_TARGET, LOAD_TARGET, STEP_TARGET = 5.0, 2.0, 16.0     # s, s, ms: issue 38, point 2
RIGHT_STEPS = 200

# In the page: the time its key handler and the layout it forces take, per key (performance.now()).
KEY_TIMES = """var key = arguments[0], times = [];
for (var n = 0; n < arguments[1]; n++) {
  var start = performance.now();
  document.body.dispatchEvent(new KeyboardEvent('keydown', { key: key, bubbles: true }));
  document.body.getBoundingClientRect();
  times.push(performance.now() - start);
}
return times;"""


def write_traces(folder: Path, robots: int, steps: int) -> list[str]:
    traces = []
    for seed in range(1, robots + 1):
        script = folder / ("robot%d.script" % seed)
        script.write_text(api.make_script([SUPERVISOR], steps, seed))
        trace = folder / ("robot%d.trace" % seed)
        trace.write_text("".join(line + "\n" for line in api.trace([SUPERVISOR], str(script), seed=seed)))
        traces.append(str(trace))
    return traces


def write_page(traces: list[str], page: Path) -> dict:
    """``swarmvm inspect`` in a process of its own: its wall time and peak resident memory."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "swarmvm", "inspect", SUPERVISOR, *traces, "-o", str(page)],
                   check=True, stdout=subprocess.DEVNULL)
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024     # Linux: kB
    return dict(write_s=round(seconds, 2), bytes=page.stat().st_size, writer_peak_bytes=peak,
                trace_bytes=sum(Path(t).stat().st_size for t in traces))


def browser_figures(page: Path) -> dict:
    browser = Browser()
    try:
        browser.open(page)
        script = browser.driver.execute_script
        loaded = script("return performance.getEntriesByType('navigation')[0].loadEventEnd") / 1000
        right = script(KEY_TIMES, "ArrowRight", RIGHT_STEPS)
        assert script("return document.body.dataset.step") == str(RIGHT_STEPS)
        end = script(KEY_TIMES, "End", 1)[0]
        assert script("return document.body.dataset.step") == str(STEPS)
        down = script(KEY_TIMES, "ArrowDown", 1)[0]
        assert script("return document.body.dataset.robot") == "1"
        return dict(load_s=round(loaded, 3), right_ms=round(sum(right) / len(right), 2),
                    right_worst_ms=round(max(right), 2), end_ms=round(end, 2), down_ms=round(down, 2))
    finally:
        browser.quit()


def verdict(value: float, target: float, unit: str) -> str:
    return "target %g %s: %s" % (target, unit, "met" if value <= target else "MISSED")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_json_option(parser)
    args = parser.parse_args()
    figures: dict = dict(robots=ROBOTS, steps=STEPS)
    with tempfile.TemporaryDirectory(prefix="swarmvm-inspect-bench-") as folder:
        start = time.perf_counter()
        traces = write_traces(Path(folder), ROBOTS, STEPS)
        print("inspect page: %d traces of %d steps written by the reference VM in %.0f s"
              % (ROBOTS, STEPS, time.perf_counter() - start))
        figures.update(write_page(traces, Path(folder) / "report.html"))
        why = missing()
        if why is None:
            figures.update(browser_figures(Path(folder) / "report.html"))
    print("inspect page, %d robots x %d steps: written in %.2f s (%s), %d bytes, writer's peak memory %.0f MB "
          "(the traces: %.0f MB)" % (ROBOTS, STEPS, figures["write_s"], verdict(figures["write_s"], WRITE_TARGET, "s"),
                                     figures["bytes"], figures["writer_peak_bytes"] / 1e6, figures["trace_bytes"] / 1e6))
    if why is None:
        print("Chromium: loaded in %.2f s (%s)" % (figures["load_s"], verdict(figures["load_s"], LOAD_TARGET, "s")))
        for key, label in (("right_ms", "a step (Right key, mean of %d)" % RIGHT_STEPS),
                           ("right_worst_ms", "a step (Right key, worst of %d)" % RIGHT_STEPS),
                           ("end_ms", "a jump to the last step (End)"), ("down_ms", "the next robot (Down)")):
            print("Chromium: %s drawn in %.1f ms (%s)" % (label, figures[key], verdict(figures[key], STEP_TARGET, "ms")))
    else:
        print("Chromium: not measured: %s" % why)
    write_figures(args.json, figures)


if __name__ == "__main__":
    main()
