"""The timeline's marks in real Chromium (issue 38, point 3; docs/inspect.md, "The timeline"): `m`
and the *mark* button mark the step shown or unmark it, each mark is drawn on the timeline (a
purple line over the lanes) and listed beside its buttons, `.` and `,` (and *next mark*,
*previous mark*) go to the next and previous one, and the page's address keeps them, so that a
link opened afresh, or an address edited, shows the same marks."""

from selenium.webdriver.common.action_chains import ActionChains
from selenium.common.exceptions import TimeoutException
from selenium.webdriver.support.ui import WebDriverWait

from inspect_cases import EXAMPLE, write_trace
from swarmvm import api

MARK = (106, 27, 154)            # #6a1b9a, inspect.js' paintMarks
COLUMN = """var c = document.getElementById('timeline'), x = c.getContext('2d');
var i = arguments[0], d = x.getImageData(Math.round(i * c.width / arguments[1]), c.height - 3, 1, 1).data;
return [d[0], d[1], d[2]];"""


def page(tmp_path):
    traces = [write_trace(tmp_path, EXAMPLE, 40, seed, "robot%d.trace" % seed) for seed in (1, 2)]
    api.inspect(str(EXAMPLE), [str(t) for t in traces], str(tmp_path / "p.html"))
    return tmp_path / "p.html"


def load(browser, url):
    browser.driver.get("about:blank")
    browser.driver.get(url)
    WebDriverWait(browser.driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))


def step(browser):
    return int(browser.driver.execute_script("return document.body.dataset.step"))


def press(browser, keys):
    ActionChains(browser.driver).send_keys(keys).perform()


def listed(browser):
    return [b.text for b in browser.driver.find_elements("css selector", "#markList button")]


def address_holds(browser, marks):
    """Whether the page's address comes to hold the step shown and ``marks`` (it follows the
    view 100 ms after it rests)."""
    want = "#step=%d&robot=robot1.trace" % step(browser) + ("&marks=" + marks if marks else "")
    try:
        WebDriverWait(browser.driver, 5).until(lambda d: d.execute_script("return location.hash") == want)
    except TimeoutException:
        return False
    return True


def test_marks_are_set_drawn_visited_and_removed(browser, tmp_path):
    url = page(tmp_path).resolve().as_uri()
    load(browser, url + "#step=5")
    driver = browser.driver
    assert driver.execute_script(COLUMN, 30, 40) != list(MARK)
    press(browser, "m")                                        # step 5 marked with the key
    press(browser, "g")                                        # the go-to box: the mark stays
    press(browser, "30\n")
    assert step(browser) == 30 and listed(browser) == ["5"]
    driver.find_element("id", "mark").click()                  # step 30 with the button
    assert listed(browser) == ["5", "30"] and address_holds(browser, "5,30")
    assert driver.find_element("id", "mark").text == "unmark"
    assert driver.execute_script(COLUMN, 5, 40) == list(MARK)   # drawn on the timeline, under the lanes' cursor
    press(browser, "\ue011")                                   # Home, then the next marks, one past the last
    seen = []
    for key in "...,":
        press(browser, key)
        seen.append(step(browser))
    assert seen == [5, 30, 30, 5]
    press(browser, ".")
    press(browser, ".")
    assert "no next mark" in driver.find_element("id", "status").text
    driver.find_element("id", "prevMark").click()
    assert step(browser) == 5
    driver.find_element("id", "nextMark").click()
    assert step(browser) == 30
    press(browser, "m")                                        # unmarked: gone from the list, the address, the timeline
    assert listed(browser) == ["5"] and address_holds(browser, "5")
    assert driver.find_element("id", "mark").text == "mark"
    assert driver.execute_script(COLUMN, 30, 40) != list(MARK)
    driver.find_elements("css selector", "#markList button")[0].click()
    assert step(browser) == 5


def test_a_link_shares_its_marks(browser, tmp_path):
    """An address holding marks, opened afresh: listed, drawn, visited; one past the page's steps is
    listed but not drawn nor visited; an address edited to other marks shows those."""
    url = page(tmp_path).resolve().as_uri()
    load(browser, url + "#step=3&marks=22,12,x,12,900")
    driver = browser.driver
    assert listed(browser) == ["12", "22", "900"]
    assert not driver.find_elements("css selector", "#markList button")[2].is_enabled()
    assert [driver.execute_script(COLUMN, i, 40) == list(MARK) for i in (12, 22)] == [True, True]
    for expected in (12, 22, 22):
        press(browser, ".")
        assert step(browser) == expected
    assert address_holds(browser, "12,22,900")
    driver.execute_script("location.hash = '#step=4&marks=7'")
    WebDriverWait(driver, 5).until(lambda d: listed(browser) == ["7"])
    assert driver.execute_script(COLUMN, 7, 40) == list(MARK) and driver.execute_script(COLUMN, 12, 40) != list(MARK)
