"""The inspector's page in a real browser (Debian's Chromium, headless, through Selenium): pages
made from corpus supervisors and traces of the Python VM and of the C host program, stepped
through with the keyboard and the buttons; what is highlighted must be what the trace says, the
page must fetch nothing, and user text must stay text. Screenshots of a few views are kept in
build/inspect-screenshots/ (CI artifacts; docs/img/inspect.png is one of them)."""

import time

import pytest

from inspect_cases import EXAMPLE, FLIPFLOP, NETWORK_WORKER, SCREENSHOTS, trace_lines, write_trace
from swarmvm import api

CURRENT = """return Array.from(document.querySelectorAll('figure.sup')).map(function (f) {
  return Array.from(f.querySelectorAll('g.node.%s title')).map(function (t) { return t.textContent; }); });"""


def press(browser, *keys):
    from selenium.webdriver.common.action_chains import ActionChains
    chain = ActionChains(browser.driver)
    for key in keys:
        chain.send_keys(key)
    chain.perform()


def step(browser) -> int:
    return int(browser.driver.execute_script("return document.body.dataset.step"))


def highlighted(browser, cls="cur"):
    return browser.driver.execute_script(CURRENT % cls)


def panel_cells(browser, cls):
    return browser.driver.execute_script(
        "return Array.from(document.querySelectorAll('#panels td.%s')).map(function (td) { return td.textContent; })"
        % cls)


def screenshot(browser, name):
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    browser.driver.save_screenshot(str(SCREENSHOTS / name))


def assert_follows(browser, rows):
    """Step forward through every row with the Right key: the highlighted state of each
    supervisor, the events fired and the violation counter are the trace's."""
    from selenium.webdriver.common.keys import Keys
    assert step(browser) == 0 and highlighted(browser) == [["q0"] for _ in rows[0][2]]
    for number, events, states, violations in rows:
        press(browser, Keys.ARROW_RIGHT)
        assert step(browser) == number
        assert highlighted(browser) == [["q%d" % q] for q in states]
        inputs, chosen = panel_cells(browser, "inputs")[0], panel_cells(browser, "chosen")[0]
        assert [w for w in (inputs + " " + chosen).split() if w != "none"] == events
        assert panel_cells(browser, "violations")[0].split()[0] == str(violations)


@pytest.mark.parametrize("supervisor", [FLIPFLOP, EXAMPLE, NETWORK_WORKER], ids=lambda p: p.stem)
def test_the_highlighted_states_follow_a_python_vm_trace(supervisor, browser, tmp_path):
    trace = write_trace(tmp_path, supervisor, 25, 5, "robot.trace", density=0.4)
    api.inspect(str(supervisor), [str(trace)], str(tmp_path / "p.html"))
    browser.open(tmp_path / "p.html")
    assert_follows(browser, trace_lines(trace))
    screenshot(browser, "one-robot-%s.png" % supervisor.stem)
    assert browser.driver.execute_script("return performance.getEntriesByType('resource').length") == 0


def test_the_highlighted_states_follow_a_c_host_trace(browser, tmp_path):
    """The C VM built on the host (tests/conformance/c_harness.py) prints a trace the page reads;
    compared with the Python VM's, the two are the same run."""
    from conformance import c_harness
    from conformance.cases import batch, reference
    b = batch(str(FLIPFLOP))
    traces, info = c_harness.parse(c_harness.run_host(c_harness.build_host(b, tmp_path / "build")))
    assert info["end"]
    (tmp_path / "c_host.trace").write_text("".join(line + "\n" for line in traces[(0, 0)]))
    (tmp_path / "python.trace").write_text("".join(line + "\n" for line in reference(b, b.runs[0])))
    api.inspect(str(FLIPFLOP), [str(tmp_path / "c_host.trace"), str(tmp_path / "python.trace")],
                str(tmp_path / "p.html"), compare=True)
    browser.open(tmp_path / "p.html")
    assert "the two runs are identical" in browser.driver.find_element("id", "summary").text
    assert_follows(browser, trace_lines(tmp_path / "c_host.trace"))


def test_keyboard_buttons_and_jumps(browser, tmp_path):
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import Select
    trace = write_trace(tmp_path, FLIPFLOP, 60, 3, "robot.trace", density=0.4)
    rows = trace_lines(trace)
    api.inspect(str(FLIPFLOP), [str(trace)], str(tmp_path / "p.html"))
    browser.open(tmp_path / "p.html")
    press(browser, Keys.END)
    assert step(browser) == 60
    press(browser, Keys.HOME)
    assert step(browser) == 0
    from selenium.webdriver.common.action_chains import ActionChains
    ActionChains(browser.driver).key_down(Keys.SHIFT).send_keys(Keys.ARROW_RIGHT).key_up(Keys.SHIFT).perform()
    assert step(browser) == 10
    press(browser, Keys.ARROW_LEFT)
    assert step(browser) == 9
    violated = [n for (n, _e, _s, v), before in zip(rows, [0] + [r[3] for r in rows]) if v > before]
    press(browser, "v")
    assert step(browser) == next(n for n in violated if n > 9)
    press(browser, "V")
    assert step(browser) == max(n for n in violated if n < 9)
    Select(browser.driver.find_element("id", "event")).select_by_visible_text("EV_flop (uncontrollable)")
    press(browser, Keys.HOME, "e")
    flops = [n for n, events, _s, _v in rows if "EV_flop" in events]
    assert step(browser) == flops[0]
    browser.driver.find_element("id", "nextEvent").click()
    assert step(browser) == flops[1]
    browser.driver.find_element("id", "filter").click()
    logged = browser.driver.execute_script(
        "return Array.from(document.querySelectorAll('#logTable tr')).slice(1).map(function (r) {"
        " return +r.cells[0].textContent; })")
    assert logged and all(n in flops for n in logged)
    screenshot(browser, "filtered-by-event.png")
    press(browser, Keys.HOME, " ")                        # play at 64 steps/s, then pause
    browser.driver.execute_script("document.getElementById('speed').value = '64'")
    time.sleep(0.5)
    press(browser, " ")
    paused = step(browser)
    time.sleep(0.3)
    assert 0 < paused == step(browser)


def test_a_swarm_counts_robots_per_state(browser, tmp_path):
    traces = [write_trace(tmp_path, EXAMPLE, 40, seed, "robot%d.trace" % seed) for seed in range(1, 6)]
    api.inspect(str(EXAMPLE), [str(t) for t in traces], str(tmp_path / "p.html"))
    browser.open(tmp_path / "p.html")
    browser.driver.find_element("id", "slider").click()        # the middle of the timeline
    at = step(browser)
    assert 0 < at < 40
    expected = [{} for _ in range(4)]
    for trace in traces:
        for s, q in enumerate(trace_lines(trace)[at - 1][2]):
            expected[s]["q%d" % q] = expected[s].get("q%d" % q, 0) + 1
    counts = browser.driver.execute_script("""return Array.from(document.querySelectorAll('figure.sup')).map(
      function (f) { var c = {}; f.querySelectorAll('g.node').forEach(function (g) {
        var t = g.querySelector('text.count'); if (t && t.textContent) c[g.querySelector('title').textContent] =
          +t.textContent.slice(1); }); return c; });""")
    assert counts == [{q: n for q, n in e.items()} for e in expected]
    press(browser, "\ue015")                                    # Down: the next robot's states drawn
    assert highlighted(browser) == [["q%d" % q] for q in trace_lines(traces[1])[at - 1][2]]
    screenshot(browser, "swarm.png")


def test_two_runs_compared_side_by_side(browser, tmp_path):
    a, b = write_trace(tmp_path, FLIPFLOP, 40, 1, "seed1.trace"), write_trace(tmp_path, FLIPFLOP, 40, 2, "seed2.trace")
    first = next(n for n, (x, y) in enumerate(zip(a.read_text().splitlines(), b.read_text().splitlines()), 1)
                 if x != y)
    api.inspect(str(FLIPFLOP), [str(a), str(b)], str(tmp_path / "p.html"), compare=True)
    browser.open(tmp_path / "p.html")
    press(browser, "d")
    assert step(browser) == first
    assert browser.driver.execute_script("return document.querySelectorAll('#panels .panel').length") == 2
    here = browser.driver.execute_script("return document.querySelector('#logTable tr.here').className")
    assert "differs" in here
    assert highlighted(browser, "cur-b") == [["q%d" % q] for q in trace_lines(b)[first - 1][2]]
    screenshot(browser, "compare.png")


def test_names_holding_script_tags_show_as_text(browser, tmp_path):
    name = "</script><script>window.pwned = 1</script><b>bold</b>"
    trace = write_trace(tmp_path, EXAMPLE, 5, 1, "<script>window.pwned=2<script>.trace")
    api.inspect(str(EXAMPLE), [str(trace)], str(tmp_path / "p.html"), name=name)
    browser.open(tmp_path / "p.html")
    driver = browser.driver
    assert driver.execute_script("return window.pwned === undefined && document.querySelectorAll('b').length === 0")
    assert driver.find_element("css selector", "h1").text == name
    assert driver.find_element("css selector", "#laneNames span").text == trace.name
    assert driver.execute_script("return document.title") == name + ": swarmvm inspect"


FIRED = """return Array.from(document.querySelectorAll('figure.sup')).map(function (f) {
  return Array.from(f.querySelectorAll('g.edge.%s')).map(function (g) {
    return g.querySelector('title').textContent + ' ' + g.querySelector('text').textContent; }).sort(); });"""


def taken(model, before, events):
    """Per supervisor, the drawn edges ("qA->qB name") the events of one step take from ``before``."""
    states, edges = list(before), [set() for _ in model.supervisors]
    for name in events:
        event = model.events.index(name[3:])
        for s, sup in enumerate(model.supervisors):
            targets = [t for e, t, _ in sup.states[states[s]] if e == event]
            if event in sup.alphabet and targets:
                edges[s].add("q%d->q%d %s" % (states[s], targets[0], name[3:]))
                states[s] = targets[0]
    return [sorted(e) for e in edges]


def test_every_transition_taken_is_drawn_for_both_runs(browser, tmp_path, monkeypatch):
    """Two runs of the bundled example compared on a page whose window starts after their first difference:
    the summary still says where they first differ; at a step where a supervisor takes an input and
    then the chosen event, both its transitions are drawn thick, and the second run's too."""
    from swarmvm.inspector import page as inspect_page
    from selenium.webdriver.common.keys import Keys
    monkeypatch.setattr(inspect_page, "ROBOT_STEPS", 40)            # 2 traces: steps 11 to 30 kept
    a, b = (write_trace(tmp_path, EXAMPLE, 30, seed, "seed%d.trace" % seed, density=0.4) for seed in (1, 2))
    api.inspect(str(EXAMPLE), [str(a), str(b)], str(tmp_path / "p.html"), compare=True, first_step=11)
    model = api.compile_model([str(EXAMPLE)]).model
    rows_a, rows_b = trace_lines(a), trace_lines(b)
    first = next(n for n, (x, y) in enumerate(zip(rows_a, rows_b), 1) if x != y)
    assert first < 11
    browser.open(tmp_path / "p.html")
    summary = browser.driver.find_element("id", "summary").text
    assert "identical" not in summary and "first differ at step %d" % first in summary
    twice = [n for n in range(12, 31) if any(len(edges) > 1 for edges in taken(model, rows_a[n - 2][2], rows_a[n - 1][1]))]
    at = twice[0]
    press(browser, *[Keys.ARROW_RIGHT] * (at - 10))
    assert step(browser) == at
    script = browser.driver.execute_script
    assert script(FIRED % "fired") == taken(model, rows_a[at - 2][2], rows_a[at - 1][1])
    assert script(FIRED % "fired-b") == taken(model, rows_b[at - 2][2], rows_b[at - 1][1])
    assert any(script(FIRED % "fired-b"))
    screenshot(browser, "transitions-taken.png")


def test_next_event_and_violation_stay_on_the_robot_shown(browser, tmp_path):
    """robot a has violations at steps 3 and 8, robot b at 5 and 10: from a, v goes to 3 then 8 on
    a (not to b's 5), then, a having none later, to b's 10; V from there stays on b (5), then goes
    back to a (3); past the last of all, v stays and says there is none. EV_flip: a at 2 and 9,
    b at 4: e goes to a's 2 and 9, then, none later in any robot, stays."""
    from selenium.webdriver.support.ui import Select

    def trace(name, violated, flips):
        count, lines = 0, []
        for n in range(1, 13):
            count += n in violated
            lines.append("%d %s 0,0 %d\n" % (n, "EV_flip" if n in flips else "-", count))
        (tmp_path / name).write_text("".join(lines))
        return str(tmp_path / name)

    traces = [trace("a.trace", (3, 8), (2, 9)), trace("b.trace", (5, 10), (4,))]
    api.inspect(str(FLIPFLOP), traces, str(tmp_path / "p.html"))
    browser.open(tmp_path / "p.html")

    def robot():
        return int(browser.driver.execute_script("return document.body.dataset.robot"))

    def status():
        return browser.driver.find_element("id", "status").text

    seen = []
    for key in "vvvVV":
        press(browser, key)
        seen.append((robot(), step(browser)))
    assert seen == [(0, 3), (0, 8), (1, 10), (1, 5), (0, 3)]
    assert status() == "no previous violation in b.trace: a.trace's shown"
    press(browser, "v", "v")                                    # a's 8, then b's 10 (a has none later)
    assert (robot(), step(browser)) == (1, 10) and status() == "no next violation in a.trace: b.trace's shown"
    press(browser, "v")
    assert (robot(), step(browser)) == (1, 10) and status() == "no next violation in any robot"
    Select(browser.driver.find_element("id", "event")).select_by_visible_text("EV_flip (uncontrollable)")
    press(browser, "\ue011", "\ue013")                          # Home, Up: robot a at the reset
    seen = []
    for key in "eee":
        press(browser, key)
        seen.append((robot(), step(browser)))
    assert seen == [(0, 2), (0, 9), (0, 9)] and status() == "no next EV_flip in any robot"
