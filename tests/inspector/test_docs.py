"""Every command docs/inspect.md shows runs as shown (from a folder holding the repository's
examples/), and the pages they write are what the page says: two robots' traces, then the same
two compared, then the supervisors alone for the simulator. In Chromium, the report is screenshot
at step 20 (docs/img/inspect.png was taken so, then reduced), and the simulator's page fired on,
its script saved and replayed by the documented ``swarmvm trace``."""

import json
import re
import subprocess
import time

from inspect_cases import ROOT, SCREENSHOTS, trace_lines
from swarmvm.inspector.encoding import decode

DOC = ROOT / "docs" / "inspect.md"


def commands() -> list:
    blocks = re.findall(r"```sh\n(.*?)```", DOC.read_text(), re.S)
    return [line for block in blocks for line in block.splitlines() if line.startswith("swarmvm ")]


def page_data(path):
    return json.loads(re.search(r'<script id="data" type="application/json">(.*?)</script>', path.read_text(),
                                re.S).group(1))


def test_the_commands_of_docs_inspect_run(tmp_path):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    shown = commands()
    assert [c.split()[1] for c in shown] == ["script", "trace", "script", "trace", "inspect", "inspect", "inspect",
                                             "trace"]
    for command in shown[:-1]:          # the last replays the simulator's script: test_the_simulator_script_replays_as_documented
        run = subprocess.run(["bash", "-c", "set -o pipefail; " + command], cwd=tmp_path, capture_output=True,
                             text=True)
        assert run.returncode == 0, (command, run.stderr)
    report, compare = page_data(tmp_path / "report.html"), page_data(tmp_path / "compare.html")
    assert [r["name"] for r in report["runs"]] == ["robot1.trace", "robot2.trace"]
    assert [len(decode(report, r)) for r in report["runs"]] == [501, 501]      # the reset, then every step
    assert len(trace_lines(tmp_path / "robot1.trace")) == 500
    assert compare["compare"] is True and compare["difference"] == 1


def test_the_screenshot_view(tmp_path, browser):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    for command in commands()[:5]:
        subprocess.run(["bash", "-c", command], cwd=tmp_path, check=True, capture_output=True)
    browser.open(tmp_path / "report.html")
    ActionChains(browser.driver).send_keys(Keys.ARROW_RIGHT * 20).perform()
    assert browser.driver.execute_script("return document.body.dataset.step") == "20"
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    browser.driver.save_screenshot(str(SCREENSHOTS / "docs-report.png"))


def test_the_simulator_script_replays_as_documented(tmp_path, browser):
    """The simulator's page of the documented command, fired on for 12 steps in Chromium (the
    VM's choice each time, an input where one is enabled), its script saved into the folder and
    replayed by the documented ``swarmvm trace``: the same lines as the page's."""
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    page, replay = commands()[-2:]
    subprocess.run(["bash", "-c", page], cwd=tmp_path, check=True, capture_output=True)
    browser.open(tmp_path / "simulator.html")
    driver = browser.driver
    for _ in range(12):
        driver.execute_script("""var input = document.querySelector('#simEvents button.uncontrollable:enabled');
          if (input) input.click();
          document.getElementById('simStep').click();""")
    lines = driver.execute_script(
        "return Array.from(document.querySelectorAll('#simLog td')).map(function (td) { return td.textContent; })")
    assert len(lines) == 12
    driver.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(tmp_path)})
    driver.find_element("id", "simSave").click()
    script = tmp_path / "energy_worker.script"
    for _ in range(100):
        if script.exists() and script.stat().st_size:
            break
        time.sleep(0.05)
    run = subprocess.run(["bash", "-c", "set -o pipefail; " + replay], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "replay.trace").read_text().splitlines() == lines
