"""docs/inspect.md's screenshots of the inspector's page at a laptop's size (1366 x 768) and a
phone's (390 x 844), taken in headless Chromium (issue 38, point 6).

The pages are made as a user makes them (random scripts, the reference VM's traces,
``swarmvm inspect``) from the bundled example and a corpus supervisor with large drawings; each
view is a page, a window size, an address (a step, a robot, marks) and the section scrolled to.
tests/inspector/test_layout.py measures the layout of the same pages at the same sizes (and keeps
its own screenshots in build/inspect-screenshots/layout/), and runs this script into a scratch
folder to check that its images are the size of those committed in docs/img/. Chromium's PNGs
are not byte-identical from one run to the next, so nothing compares their bytes.

    python3 scripts/inspect_screenshots.py            # rewrite docs/img/inspect-{laptop,phone}*.png
    python3 scripts/inspect_screenshots.py FOLDER     # write them into FOLDER instead
"""

import argparse
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "inspector"))

from browser import Browser  # noqa: E402
from inspect_cases import EXAMPLE, NETWORK_WORKER, write_trace  # noqa: E402

from swarmvm import api  # noqa: E402

SIZES = {"laptop": (1366, 768), "phone": (390, 844)}
# The page's section scrolled to the top of the window, under the sticky controls.
SCROLL_TO = """var top = document.querySelector(arguments[0]).getBoundingClientRect().top;
window.scrollTo(0, top + window.scrollY - document.getElementById('controls').offsetHeight - 8);"""


@dataclass(frozen=True)
class View:
    """One screenshot: which page, at which size, at which address, scrolled to which section
    (a CSS selector; empty: the top of the page)."""
    page: str
    size: str
    address: str
    section: str = ""


VIEWS = {
    "inspect-laptop.png": View("compare", "laptop", "#step=25&marks=7,30"),
    "inspect-phone.png": View("swarm", "phone", "#step=20&robot=robot2.trace&marks=9,31"),
    "inspect-phone-drawing.png": View("network", "phone", "#step=20", 'figure.sup[data-sup="5"]'),
    "inspect-phone-compare.png": View("compare", "phone", "#step=27", "#log"),
}


def changed(folder: Path, trace: Path, other: Path, at: int) -> Path:
    """``trace``'s run with the inputs of ``other``'s script from step ``at`` on (the scripts
    write_trace left beside them): the two runs are the same up to there."""
    def steps(path: Path) -> list[str]:
        return [line for line in path.with_name(path.name + ".script").read_text().splitlines()
                if not line.startswith("#")]
    script = folder / "changed.script"
    script.write_text("".join(line + "\n" for line in steps(trace)[:at - 1] + steps(other)[at - 1:]))
    path = folder / "changed.trace"
    path.write_text("".join(line + "\n" for line in api.trace([str(EXAMPLE)], str(script), seed=1)))
    return path


def pages(folder: Path) -> dict[str, Path]:
    """The pages the views show: a swarm of five robots of the bundled example, one of its runs
    compared with the same run given other inputs from step 25 on, and three robots of
    network_worker (8 supervisors, the widest 4,438 pt)."""
    swarm = [write_trace(folder, EXAMPLE, 40, seed, "robot%d.trace" % seed) for seed in range(1, 6)]
    network = [write_trace(folder, NETWORK_WORKER, 60, seed, "nw%d.trace" % seed, density=0.1) for seed in (1, 2, 3)]
    made = {"swarm": folder / "swarm.html", "compare": folder / "compare.html", "network": folder / "network.html"}
    api.inspect(str(EXAMPLE), [str(t) for t in swarm], str(made["swarm"]))
    api.inspect(str(EXAMPLE), [str(swarm[0]), str(changed(folder, swarm[0], swarm[1], 25))], str(made["compare"]),
                compare=True)
    api.inspect(str(NETWORK_WORKER), [str(t) for t in network], str(made["network"]))
    return made


def set_size(driver: Any, size: str) -> None:
    """The window's size in CSS pixels, one device pixel each; a phone's is a mobile viewport
    (the page's <meta name="viewport"> applies)."""
    width, height = SIZES[size]
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                           {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": size == "phone"})


def show(browser: Browser, page: Path, view: View) -> None:
    """``page`` opened at the view's address and size, scrolled to its section."""
    set_size(browser.driver, view.size)
    browser.driver.get("about:blank")                  # the address's hash is read when the page loads
    browser.driver.get(page.resolve().as_uri() + view.address)
    from selenium.webdriver.support.ui import WebDriverWait
    WebDriverWait(browser.driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    if view.section:
        browser.driver.execute_script(SCROLL_TO, view.section)
    time.sleep(1.5)                                   # the address written back, overlay scroll bars faded


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", default=str(ROOT / "docs" / "img"), help="where the PNGs go")
    folder = Path(parser.parse_args(argv).folder)
    folder.mkdir(parents=True, exist_ok=True)
    browser = Browser()
    try:
        with tempfile.TemporaryDirectory(prefix="swarmvm-screenshots-") as scratch:
            made = pages(Path(scratch))
            for name, view in VIEWS.items():
                show(browser, made[view.page], view)
                browser.driver.save_screenshot(str(folder / name))
                print(folder / name)
    finally:
        browser.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
