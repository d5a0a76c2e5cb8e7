"""The inspector's page laid out at a laptop's size (1366 x 768) and a phone's (390 x 844), in
real Chromium (issue 38, point 6): the pages of scripts/inspect_screenshots.py (a swarm of the
bundled example, two of its runs compared, network_worker's large drawings), each measured from
the DOM at both sizes: nothing wider than the window, every drawing's labels at a readable size
on screen (a drawing wider than its box pans in it, its current state scrolled into view), lanes
tall enough to tap on a phone and a tap on one showing that robot, the chart of robots per state
under the lanes, the trace's table within its box, every control within the window. Screenshots of each page at each size are kept in
build/inspect-screenshots/layout/ (printed); the script's own, committed in docs/img/, are checked
to be the size it makes."""

import struct
import subprocess
import sys

import pytest

from inspect_cases import ROOT, SCREENSHOTS

sys.path.insert(0, str(ROOT / "scripts"))
import inspect_screenshots as shots  # noqa: E402

READABLE = 11          # px: a label's size on screen under which a drawing pans instead (inspect.js)
TAP = 16               # px: a lane a finger can tap
PAGES = ("swarm", "compare", "network")
KEPT = SCREENSHOTS / "layout"

MEASURE = """
var w = window.innerWidth, laneBox = document.getElementById('laneBox');
var lane = parseFloat(getComputedStyle(laneBox).getPropertyValue('--lane'));
var figures = Array.from(document.querySelectorAll('figure.sup')).map(function (f) {
  var svg = f.querySelector('svg'), font = parseFloat(svg.querySelector('text').getAttribute('font-size'));
  var r = f.getBoundingClientRect(), c = f.querySelector('g.node.cur ellipse').getBoundingClientRect();
  return { label: font * svg.getBoundingClientRect().width / svg.viewBox.baseVal.width, left: r.left, right: r.right,
    width: r.width, pans: f.scrollWidth > f.clientWidth,
    curInView: c.left >= r.left && c.right <= r.right && c.top >= r.top && c.bottom <= r.bottom };
});
function box(id) { var r = document.getElementById(id).getBoundingClientRect(); return { left: r.left, right: r.right, width: r.width }; }
var controls = Array.from(document.querySelectorAll('#controls > *, #controls label > *, #zoom > *')).filter(
  function (e) { return !e.hidden && e.getClientRects().length; }).map(function (e) {
  var r = e.getBoundingClientRect(); return [e.id || e.tagName, r.left, r.right]; });
return { inner: w, scrollWidth: Math.max(document.documentElement.scrollWidth, document.body.scrollWidth),
  figures: figures, drawings: box('drawings').width,
  laneNames: Array.from(document.querySelectorAll('#laneNames .lane')).map(function (s) { return s.getBoundingClientRect().height; }),
  lane: lane, canvas: document.getElementById('timeline').getBoundingClientRect().height,
  lanes: document.querySelectorAll('#laneNames .lane').length,
  log: box('log'), logTable: box('logTable'), runs: box('runs'), timeline: box('timeline'), chart: box('chart'),
  controls: controls, nav: document.getElementById('controls').getBoundingClientRect().height, height: window.innerHeight };
"""


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    return shots.pages(tmp_path_factory.mktemp("pages"))


@pytest.fixture
def sized(browser):
    yield browser
    browser.driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


def keep(browser, name):
    KEPT.mkdir(parents=True, exist_ok=True)
    browser.driver.save_screenshot(str(KEPT / name))
    print("screenshot:", KEPT / name)


@pytest.mark.parametrize("size", sorted(shots.SIZES))
@pytest.mark.parametrize("page", PAGES)
def test_the_page_fits_the_window(page, size, pages, sized):
    shots.show(sized, pages[page], shots.View(page, size, "#step=20&marks=5,30"))
    keep(sized, "%s-%s.png" % (page, size))
    m = sized.driver.execute_script(MEASURE)
    width, height = shots.SIZES[size]
    assert m["inner"] == width and m["height"] == height
    assert m["scrollWidth"] <= m["inner"], "the page is wider than the window"
    for s, figure in enumerate(m["figures"]):
        assert figure["label"] >= READABLE - 0.05, "supervisor %d's labels are %.1f px on screen" % (s, figure["label"])
        assert 0 <= figure["left"] and figure["right"] <= m["inner"], "supervisor %d's box leaves the window" % s
        if figure["pans"]:
            assert figure["curInView"], "supervisor %d: its current state is out of its box's view" % s
        if size == "phone":                                   # as wide as the section: filled, not shrunk
            assert figure["width"] == pytest.approx(m["drawings"], abs=1)
    assert m["lanes"] and all(h == m["lane"] for h in m["laneNames"])
    assert m["canvas"] == pytest.approx(m["lanes"] * m["lane"] + 4 + 2, abs=1)   # the canvas' lanes beside their names
    assert m["chart"] == m["timeline"], "the chart's steps are not under the lanes'"
    if size == "phone":
        assert m["lane"] >= TAP
        assert m["nav"] <= m["height"] / 4, "the sticky controls take %d px of %d" % (m["nav"], m["height"])
    assert m["logTable"]["width"] <= m["log"]["width"] + 0.5, "the trace's table is wider than its box"
    assert m["runs"]["right"] <= m["inner"] and m["log"]["right"] <= m["inner"]
    outside = [c for c in m["controls"] if c[1] < 0 or c[2] > m["inner"]]
    assert outside == []


def test_a_wide_drawing_pans_on_a_phone_and_its_state_stays_in_view(pages, sized):
    """network_worker's supervisor 5 (1,333 pt) on a phone: at a readable scale it is wider than
    its box, a drag pans it, and stepping on scrolls the box to the state highlighted."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    shots.show(sized, pages["network"], shots.View("network", "phone", "#step=20", 'figure.sup[data-sup="5"]'))
    driver = sized.driver
    figure = driver.find_element("css selector", 'figure.sup[data-sup="5"]')
    scroll = "return [arguments[0].scrollLeft, arguments[0].scrollTop, arguments[0].scrollWidth, arguments[0].clientWidth]"
    left, top, wide, seen = driver.execute_script(scroll, figure)
    assert wide > 1.5 * seen
    ActionChains(driver).move_to_element(figure).click_and_hold().move_by_offset(-120, 0).release().perform()
    assert driver.execute_script(scroll, figure)[0] == pytest.approx(left + 120, abs=2)
    keep(sized, "network-phone-drawing.png")
    in_view = """var f = arguments[0], r = f.getBoundingClientRect(), c = f.querySelector('g.node.cur ellipse').getBoundingClientRect();
      return c.left >= r.left && c.right <= r.right && c.top >= r.top && c.bottom <= r.bottom;"""
    moved = 0
    for _ in range(40):                       # until supervisor 5 changes state out of the box's view
        state = driver.execute_script("return arguments[0].querySelector('g.node.cur title').textContent", figure)
        ActionChains(driver).send_keys(Keys.ARROW_RIGHT).perform()
        if driver.execute_script("return arguments[0].querySelector('g.node.cur title').textContent", figure) != state:
            moved += 1
            assert driver.execute_script(in_view, figure)
    assert moved


def test_a_tap_on_a_lane_shows_that_robot_on_a_phone(pages, sized):
    shots.show(sized, pages["swarm"], shots.View("swarm", "phone", "#step=20"))
    driver = sized.driver
    lane = driver.execute_script("return parseFloat(getComputedStyle(document.getElementById('laneBox'))"
                                 ".getPropertyValue('--lane'))")
    canvas = driver.find_element("id", "timeline")
    size = canvas.size
    from selenium.webdriver.common.action_chains import ActionChains
    for robot in (3, 1):                      # the middle of lane 3, then of lane 1, at three quarters of the steps
        ActionChains(driver).move_to_element_with_offset(canvas, int(size["width"] / 4),
                                                         int(2 + lane * robot + lane / 2 - size["height"] / 2)).click().perform()
        assert driver.execute_script("return document.body.dataset.robot") == str(robot)
        assert 25 <= int(driver.execute_script("return document.body.dataset.step")) <= 35


def png_size(path):
    """A PNG's width and height, from its IHDR chunk."""
    head = path.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR"
    return struct.unpack(">II", head[16:24])


def test_the_screenshot_script_makes_the_images_of_docs(tmp_path, browser):
    """scripts/inspect_screenshots.py, as docs/inspect.md shows it, into a scratch folder: one PNG
    per view, each the size of its window, the size of the one committed in docs/img/."""
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "inspect_screenshots.py"), str(tmp_path)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [str(tmp_path / name) for name in shots.VIEWS]
    for name, view in shots.VIEWS.items():
        made, committed = png_size(tmp_path / name), png_size(ROOT / "docs" / "img" / name)
        assert made == committed == shots.SIZES[view.size], name
    docs = (ROOT / "docs" / "inspect.md").read_text()
    assert all("img/%s" % name in docs for name in shots.VIEWS)
    assert "python3 scripts/inspect_screenshots.py\n" in docs

