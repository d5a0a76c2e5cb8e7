"""The inspector's page in a real browser (Debian's Chromium, headless, through Selenium): pages
made from corpus supervisors and traces of the Python VM and of the C host program, stepped
through with the keyboard and the buttons; what is highlighted must be what the trace says, the
page must fetch nothing, and user text must stay text. Screenshots of a few views are kept in
build/inspect-screenshots/ (CI artifacts; docs/img/inspect.png is one of them)."""

import time

import pytest

from inspect_cases import EXAMPLE, FLIPFLOP, HITL_LEADER, NETWORK_WORKER, SCREENSHOTS, trace_lines, write_trace
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


# The section arguments[0] at the top of the window, under the sticky controls.
SCROLL_TO = """var top = document.getElementById(arguments[0]).getBoundingClientRect().top;
window.scrollTo(0, top + window.scrollY - document.getElementById('controls').offsetHeight - 8);"""


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


def refused(model, before, events):
    """What the page says refused the events of a step fired from ``before``: "EV_x by supervisor S
    in qQ" for each supervisor holding x without a transition on it, in firing order."""
    states, said = list(before), []
    for name in events:
        event = model.events.index(name[3:])
        for s, sup in enumerate(model.supervisors):
            targets = [t for e, t, _ in sup.states[states[s]] if e == event]
            if event in sup.alphabet and not targets:
                said.append("%s by supervisor %d in q%d" % (name, s, states[s]))
            elif targets:
                states[s] = targets[0]
    return "; ".join(said)


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
    model = api.compile_model([str(FLIPFLOP)]).model           # which supervisor refused which input
    at = step(browser)
    assert panel_cells(browser, "refused") == [refused(model, rows[at - 2][2], rows[at - 1][1])]
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
    from selenium.webdriver.support.ui import Select
    Select(browser.driver.find_element("id", "depth")).select_by_value("1")   # the states one transition away
    model = api.compile_model([str(EXAMPLE)]).model
    shown = browser.driver.execute_script("""return Array.from(document.querySelectorAll('figure.sup')).map(
      function (f) { return Array.from(f.querySelectorAll('g.node')).filter(function (g) {
        return g.style.display !== 'none'; }).map(function (g) { return g.querySelector('title').textContent; })
        .filter(function (t) { return /^q\\d+$/.test(t); }).sort(); });""")
    for sup, here, drawn in zip(model.supervisors, trace_lines(traces[1])[at - 1][2], shown):
        near = {here} | {t for _e, t, _p in sup.states[here]}
        near |= {q for q, row in enumerate(sup.states) if any(t == here for _e, t, _p in row)}
        assert drawn == sorted("q%d" % q for q in near)
    width = "return document.querySelector('figure.sup svg').getBoundingClientRect().width"
    before = browser.driver.execute_script(width)
    browser.driver.find_element("css selector", "figure.sup button.zoomSup[title^='zoom in']").click()
    assert browser.driver.execute_script(width) == pytest.approx(before * 1.5, abs=2)
    browser.driver.find_element("css selector", "figure.sup button.zoomSup[title^='fit']").click()
    assert browser.driver.execute_script(width) == pytest.approx(before, abs=2)


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
    differing = [n for n, (x, y) in enumerate(zip(a.read_text().splitlines(), b.read_text().splitlines()), 1)
                 if x != y]
    seen = []
    for key in "ddD":                                      # the next two differences, then back one
        press(browser, key)
        seen.append(step(browser))
    assert seen == [differing[1], differing[2], differing[1]]
    press(browser, "\ue010")                                # End: no next difference after the last step
    press(browser, "d")
    assert step(browser) == 40 and "no next difference" in browser.driver.find_element("id", "status").text
    assert browser.driver.find_elements("css selector", "#laneNames span")[2].text == "differences"
    marked = browser.driver.execute_script(LANE_PIXELS, 2).get("173,20,87", 0)   # the differences' lane, pink
    width = browser.driver.execute_script("return document.getElementById('timeline').width")
    assert abs(marked - width * len(differing) / 40) <= 2 * len(differing)


def test_names_holding_script_tags_show_as_text(browser, tmp_path):
    """The title, a trace's and the supervisor file's names holding markup, and a URL naming the
    robot so: all text, in the header, the lanes, the simulator and its script."""
    from urllib.parse import quote
    name = "</script><script>window.pwned = 1</script><b>bold</b>"
    supervisor = tmp_path / "<b>sup<img src=x onerror=window.pwned=3>.yaml"
    supervisor.write_bytes(EXAMPLE.read_bytes())
    trace = write_trace(tmp_path, supervisor, 5, 1, "<script>window.pwned=2<script>.trace")
    api.inspect(str(supervisor), [str(trace)], str(tmp_path / "p.html"), name=name)
    driver = browser.driver
    driver.get((tmp_path / "p.html").resolve().as_uri() + "#step=3&robot=" + quote(trace.name))
    from selenium.webdriver.support.ui import WebDriverWait
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    driver.find_element("id", "simStep").click()
    pure = "return window.pwned === undefined && document.querySelectorAll('b, img').length === 0"
    assert driver.execute_script(pure)
    assert driver.find_element("css selector", "h1").text == name
    assert driver.find_element("css selector", "#laneNames span").text == trace.name
    assert driver.execute_script("return document.title") == name + ": swarmvm inspect"
    assert driver.find_element("id", "simFrom").text.startswith("From step 3 of %s;" % trace.name)
    script = driver.execute_script("return document.getElementById('simScript').textContent")
    assert script.splitlines()[1].startswith("# replay: swarmvm trace %s --script" % supervisor.name)


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
    browser.driver.find_element("id", "simSave").click()         # a script starts at step 1: not from here
    assert browser.driver.find_element("id", "simStatus").text == (
        "not saved: this page keeps the trace from step 11 on, and a script starts at step 1")


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


SIM_LINES = "return Array.from(document.querySelectorAll('#simLog td')).map(function (td) { return td.textContent; })"


# One step fired in the simulator by clicking its buttons, as a user does: some of the inputs
# that can still come in the step (each with probability 0.3, from a generator seeded with
# arguments[0]), then the VM's choice when one is enabled (the button marked so), else *end step*.
# In the page's script, so that a step costs one WebDriver call.
SIM_STEP = """var seed = arguments[0];
function random() { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648; }
for (;;) {
  var inputs = Array.from(document.querySelectorAll('#simEvents button.uncontrollable')).filter(function (b) {
    return !b.disabled && random() < 0.3; });
  if (!inputs.length) break;
  inputs[0].click();
}
(document.querySelector('#simEvents button.vm') || document.getElementById('simStep')).click();"""


def simulate(browser, steps, rng):
    """Fire ``steps`` steps in the simulator (:data:`SIM_STEP`, seeded from ``rng``)."""
    for _ in range(steps):
        browser.driver.execute_script(SIM_STEP, rng.randrange(1 << 30))


def saved_script(browser, folder):
    """Click *save script* and return the file Chromium downloaded into ``folder``."""
    browser.driver.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(folder)})
    browser.driver.find_element("id", "simSave").click()
    for _ in range(100):
        done = [p for p in folder.glob("*.script") if p.stat().st_size]
        if done:
            return done[0]
        time.sleep(0.05)
    raise AssertionError("no script downloaded into %s" % folder)


def test_the_simulator_fires_events_and_its_script_replays(browser, tmp_path):
    """On hitl_leader (up to 4 controllable events enabled at once, so the VM draws). With no
    trace, from the initial states, policy *first*: inputs and the VM's choices fired by clicking,
    undo and reset; the script saved replays under ``swarmvm trace --policy first`` to the lines
    the page shows. Then a trace of ``swarmvm trace`` opened at its step 20 (``#step=20&robot=...``
    in the URL) with its seed, policy *uniform*: fired further, the script saved holds the trace's
    first 20 steps and the new ones, and replays to the trace's first 20 lines followed by the
    page's; a controllable event other than the VM's choice is marked as such."""
    from selenium.webdriver.support.ui import Select
    import random
    from selenium.webdriver.common.keys import Keys
    rng = random.Random(7)
    api.inspect(str(HITL_LEADER), [], str(tmp_path / "alone.html"))
    browser.open(tmp_path / "alone.html")
    driver = browser.driver
    Select(driver.find_element("id", "simPolicy")).select_by_value("first")
    simulate(browser, 3, rng)
    three = driver.execute_script(SIM_LINES)
    assert len(three) == 3
    browser.driver.find_element("css selector", "#simEvents button.uncontrollable:enabled").click()
    assert "step 4 begun" in driver.find_element("id", "simFrom").text
    press(browser, "u")                                            # undo the input: back to step 3's states
    assert highlighted(browser) == [["q%s" % q] for q in three[-1].split()[2].split(",")]
    assert driver.execute_script(SIM_LINES) == three
    press(browser, "u")                                            # undo the third step
    assert driver.execute_script(SIM_LINES) == three[:2]
    driver.find_element("id", "simReset").click()
    assert driver.execute_script(SIM_LINES) == [] and highlighted(browser) == [["q0"]] * 5
    simulate(browser, 25, rng)
    lines = driver.execute_script(SIM_LINES)
    assert len(lines) == 25 and any(line.split()[1] != "-" for line in lines)
    assert highlighted(browser) == [["q%s" % q] for q in lines[-1].split()[2].split(",")]
    (tmp_path / "alone").mkdir()
    script = saved_script(browser, tmp_path / "alone")
    assert list(api.trace([str(HITL_LEADER)], str(script), seed=1, policy="first")) == lines
    assert "replays it to these states" in driver.find_element("id", "simStatus").text

    trace = write_trace(tmp_path, HITL_LEADER, 30, 4, "robot.trace", density=0.3)
    api.inspect(str(HITL_LEADER), [str(trace)], str(tmp_path / "traced.html"))
    driver.get((tmp_path / "traced.html").resolve().as_uri() + "#step=20&robot=robot.trace")
    from selenium.webdriver.support.ui import WebDriverWait
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    assert step(browser) == 20
    seed = driver.find_element("id", "simSeed")
    seed.clear()
    seed.send_keys("4", Keys.TAB)                                  # the trace's seed
    simulate(browser, 15, rng)
    lines = driver.execute_script(SIM_LINES)
    assert [int(line.split()[0]) for line in lines] == list(range(21, 36))
    (tmp_path / "traced").mkdir()
    script = saved_script(browser, tmp_path / "traced")
    assert list(api.trace([str(HITL_LEADER)], str(script), seed=4)) == trace.read_text().splitlines()[:20] + lines
    driver.execute_script(SCROLL_TO, "sim")
    screenshot(browser, "simulator.png")                            # docs/img/inspect-simulator.png, reduced
    for _ in range(30):
        other = driver.find_elements("css selector", "#simEvents button.controllable:not(.vm)")
        if other:
            other[0].click()
            assert driver.find_elements("css selector", "#simLog tr")[-1].get_attribute("class") == "offvm"
            break
        simulate(browser, 1, rng)
    else:
        raise AssertionError("no step with two controllable events enabled")
    press(browser, Keys.ARROW_LEFT)                                # the replay moved: the simulation is left
    assert step(browser) == 19 and driver.execute_script(SIM_LINES) == []


LANE_PIXELS = """var c = document.getElementById('timeline'), x = c.getContext('2d'), lane = arguments[0];
var data = x.getImageData(0, lane * 14 + 6, c.width, 1).data, colours = {};
for (var p = 0; p < data.length; p += 4) { var k = data[p] + ',' + data[p + 1] + ',' + data[p + 2]; colours[k] = (colours[k] || 0) + 1; }
return colours;"""


def test_the_timeline_labels_zooms_pans_searches_and_links(browser, tmp_path):
    """Three robots given in the shell's order (robot1, robot10, robot2): the lanes are labelled
    robot1, robot2, robot10 and drawn before any event is chosen; ``#step=5&robot=robot10.trace``
    opens that step of that robot; the go-to box goes to a step and the URL follows; ``z`` zooms in
    around the step shown, a drag pans, *all steps* shows them all; the chart's counts at the step
    are the traces'; the find box finds an event's steps and a state's entries."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import Select, WebDriverWait
    traces = [write_trace(tmp_path, EXAMPLE, 80, seed, "robot%d.trace" % seed, density=0.4) for seed in (1, 10, 2)]
    api.inspect(str(EXAMPLE), [str(t) for t in traces], str(tmp_path / "p.html"))
    driver = browser.driver
    driver.get((tmp_path / "p.html").resolve().as_uri() + "#step=5&robot=robot10.trace")
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    names = [s.text for s in driver.find_elements("css selector", "#laneNames span")]
    assert names == ["robot1.trace", "robot2.trace", "robot10.trace"]
    assert (step(browser), driver.execute_script("return document.body.dataset.robot")) == (5, "2")
    rows = {t.name: trace_lines(t) for t in traces}
    assert highlighted(browser) == [["q%d" % q] for q in rows["robot10.trace"][4][2]]
    for lane in range(3):                                  # grey where an event fired, from the start
        assert driver.execute_script(LANE_PIXELS, lane).get("144,164,174", 0) > 0
    box = driver.find_element("id", "goto")
    box.send_keys("42", Keys.ENTER)
    assert step(browser) == 42
    WebDriverWait(driver, 5).until(lambda d: d.execute_script("return location.hash") == "#step=42&robot=robot10.trace")

    def shown():
        label = driver.find_element("id", "zoomLabel").text.split()
        return int(label[1]), int(label[3])

    assert shown() == (0, 80)
    press(browser, "z", "z")
    low, high = shown()
    assert high - low == 20 and low <= 42 <= high
    timeline = driver.find_element("id", "timeline")
    ActionChains(driver).move_to_element(timeline).click_and_hold().move_by_offset(-300, 0).release().perform()
    assert shown()[0] > low and step(browser) == 42          # a drag pans, and shows no other step
    driver.find_element("id", "zoomAll").click()
    assert shown() == (0, 80)
    size = driver.execute_script("var r = arguments[0].getBoundingClientRect(); return [r.width, r.height];", timeline)
    ActionChains(driver).move_to_element_with_offset(timeline, -size[0] / 4, -size[1] / 2 + 9).click().perform()
    assert driver.execute_script("return document.body.dataset.robot") == "0"   # a click on robot1's lane
    assert abs(step(browser) - 20) <= 1
    press(browser, "g")                                    # the go-to box by its key: what is typed replaces 42
    driver.switch_to.active_element.send_keys("42", Keys.ENTER)
    press(browser, Keys.ARROW_DOWN, Keys.ARROW_DOWN)
    assert step(browser) == 42 and driver.execute_script("return document.body.dataset.robot") == "2"

    for sup in (0, 2):
        Select(driver.find_element("id", "chartSup")).select_by_value(str(sup))
        counts = {}
        for name in rows:
            q = rows[name][41][2][sup]
            counts[q] = counts.get(q, 0) + 1
        said = driver.find_element("id", "chartNow").text
        assert said == "step 42: " + ", ".join("q%d \u00d7%d" % (q, n) for q, n in sorted(counts.items()))
        legend = [s.text for s in driver.find_elements("css selector", "#chartLegend span")]
        seen = sorted({r[2][sup] for name in rows for r in rows[name]} | {0})
        assert legend == ["q%d" % q for q in seen]

    mine = rows["robot10.trace"]
    find = driver.find_element("id", "find")
    event = next(e for e in ("EV_lowEnergy", "EV_atCharger", "EV_highEnergy") if any(e in r[1] for r in mine[42:]))
    find.send_keys(event, Keys.ENTER)
    assert step(browser) == next(r[0] for r in mine[42:] if event in r[1])
    at = step(browser)
    entered = [r[0] for before, r in zip(mine, mine[1:]) if r[0] > at and r[2][1] != before[2][1]]
    state = mine[entered[0] - 1][2][1]
    find.clear()
    find.send_keys("1=q%d" % state, Keys.ENTER)
    assert step(browser) == next(n for n in entered if mine[n - 1][2][1] == state)
    driver.execute_script(SCROLL_TO, "lanes")
    screenshot(browser, "timeline.png")                             # docs/img/inspect-timeline.png, reduced
