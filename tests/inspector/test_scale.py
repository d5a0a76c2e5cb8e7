"""A swarm's run on one page (issue 38, point 2; its figures, time and size, are measured by
benchmarks/inspect_page.py, not here): 50 robots x 20,000 steps open in real Chromium, the
last step of the last robot right; the transitions drawn at every step of two runs compared are
the ones the page's packed steps take; a page of 4-byte codes reads as one of 2; and the page
writer's memory is bounded by the page it writes, not by the traces it reads."""

import tracemalloc

from inspect_cases import EXAMPLE, NETWORK_WORKER, trace_lines, write_trace
from swarmvm import api
from swarmvm.inspector import encoding, page, trace
from test_browser import FIRED, assert_follows, highlighted, panel_cells, press, step, taken

ROBOTS, STEPS = 50, 20_000


def test_fifty_robots_of_twenty_thousand_steps_on_one_page(browser, tmp_path):
    """1,000,000 robot-steps, the old page's whole limit, kept in full on one page; End, then Up
    (from the first lane to the last): robot50's step 20,000, as its trace's last line says."""
    from selenium.webdriver.common.keys import Keys
    traces = [write_trace(tmp_path, EXAMPLE, STEPS, seed, "robot%d.trace" % seed) for seed in range(1, ROBOTS + 1)]
    inspection = api.inspect(str(EXAMPLE), [str(t) for t in traces], str(tmp_path / "p.html"))
    assert inspection.kept == inspection.total == ROBOTS * STEPS
    browser.open(tmp_path / "p.html")
    press(browser, Keys.END, Keys.ARROW_UP)
    script = browser.driver.execute_script
    assert step(browser) == STEPS and script("return document.body.dataset.robot") == str(ROBOTS - 1)
    number, events, states, violations = trace_lines(traces[-1])[-1]
    assert number == STEPS
    assert script("return document.querySelector('#panels h3').textContent") == "robot%d.trace" % ROBOTS
    assert highlighted(browser) == [["q%d" % q] for q in states]
    inputs, chosen = panel_cells(browser, "inputs")[0], panel_cells(browser, "chosen")[0]
    assert [w for w in (inputs + " " + chosen).split() if w != "none"] == events
    assert panel_cells(browser, "violations")[0].split()[0] == str(violations)
    here = script("return document.querySelector('#logTable tr.here').cells[1].textContent")
    assert here == traces[-1].read_text().splitlines()[-1]
    assert script("return document.querySelectorAll('#laneNames span.lane').length") == ROBOTS
    assert "robot-steps" not in browser.driver.find_element("id", "summary").text     # nothing left out


def test_every_transition_a_step_takes_is_drawn_for_both_runs(browser, tmp_path):
    """At every step of two network_worker runs compared, the edges drawn thick (first run) and
    dashed pink (second) are the transitions the step's events take from the states before it,
    input by input, then the chosen event: a supervisor moving twice in a step has both."""
    from selenium.webdriver.common.keys import Keys
    a, b = (write_trace(tmp_path, NETWORK_WORKER, 60, seed, "r%d.trace" % seed, density=0.4) for seed in (7, 8))
    api.inspect(str(NETWORK_WORKER), [str(a), str(b)], str(tmp_path / "p.html"), compare=True)
    model = api.compile_model([str(NETWORK_WORKER)]).model
    browser.open(tmp_path / "p.html")
    before = {"fired": [0] * len(model.supervisors), "fired-b": [0] * len(model.supervisors)}
    twice = 0
    for row_a, row_b in zip(trace_lines(a), trace_lines(b)):
        press(browser, Keys.ARROW_RIGHT)
        assert step(browser) == row_a[0]
        for cls, (_n, events, states, _v) in (("fired", row_a), ("fired-b", row_b)):
            drawn = taken(model, before[cls], events)
            assert browser.driver.execute_script(FIRED % cls) == drawn, (row_a[0], cls)
            twice += sum(len({edge.split(" ")[0] for edge in edges}) > 1 for edges in drawn)
            before[cls] = states
    assert twice            # the case a straight before -> after edge missed


def test_a_page_of_four_byte_codes_reads_as_one_of_two(browser, tmp_path, monkeypatch):
    """A page whose table of steps outgrows 2-byte codes (made to, with a table of 1 row at
    most for 2-byte codes) packs them in 4 bytes, and the browser follows the trace as well."""
    monkeypatch.setattr(encoding, "SHORT", 1)
    trace_file = write_trace(tmp_path, NETWORK_WORKER, 25, 5, "robot.trace", density=0.4)
    api.inspect(str(NETWORK_WORKER), [str(trace_file)], str(tmp_path / "p.html"))
    browser.open(tmp_path / "p.html")
    assert browser.driver.execute_script(
        "return JSON.parse(document.getElementById('data').textContent).codeBytes") == 4
    assert_follows(browser, trace_lines(trace_file))


def test_the_writers_memory_is_bounded_by_the_page_not_by_the_traces(tmp_path, monkeypatch):
    """Two robots' traces of 5,000 then 20,000 steps (4x the text), the page keeping 2,000 steps
    of each either way: the peak memory Python allocates writing the page grows by under a
    quarter, where holding the traces (or their steps) would grow it about 4x. The reader's
    fixed buffers (a block of the file, the line texts and step numbers remembered) are made
    small, so that at this scale what they hold is seen to be bounded, as it is at any scale."""
    monkeypatch.setattr(trace, "BLOCK", 1 << 14)
    monkeypatch.setattr(trace, "TAILS", 1 << 8)
    monkeypatch.setattr(trace, "STEP_TEXTS", 1 << 10)
    monkeypatch.setattr(page, "ROBOT_STEPS", 2 * 2000)
    model = api.compile_model([str(EXAMPLE)]).model
    peaks, sizes = [], []
    for steps in (5000, 20_000):
        traces = [str(write_trace(tmp_path, EXAMPLE, steps, seed, "r%d-%d.trace" % (steps, seed))) for seed in (1, 2)]
        sizes.append(sum((tmp_path / t).stat().st_size for t in traces))
        tracemalloc.start()
        try:
            written = page.write_page(model, "t", traces, str(tmp_path / ("p%d.html" % steps)), False, 1)
            peaks.append(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()
        assert (written.kept, written.total) == (2 * 2000, 2 * steps)
    assert sizes[1] > 3.9 * sizes[0]
    assert peaks[1] < 1.25 * peaks[0], peaks
