"""Chromium from Debian driven by Selenium, for the inspector's page (docs/inspect.md): the
options that keep a headless browser from reaching the network on its own (no component
updates, sync or background fetches), and a fresh profile per browser."""

import os
import shutil
import tempfile
from pathlib import Path

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
OPTIONS = ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
           "--disable-component-update", "--disable-sync", "--no-first-run", "--window-size=1280,1000")


def missing() -> str | None:
    """Why no browser test can run here, or None."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install -e '.[test]')"
    for path in (CHROMIUM, CHROMEDRIVER):
        if not os.access(path, os.X_OK):
            return "%s is missing (scripts/setup.sh installs Debian's chromium and chromium-driver)" % path
    return None


class Browser:
    """A headless Chromium with its own profile folder, removed by :meth:`quit`."""

    def __init__(self) -> None:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
        self.profile = tempfile.mkdtemp(prefix="swarmvm-chromium-")
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for option in OPTIONS + ("--user-data-dir=" + self.profile,):
            options.add_argument(option)
        self.driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)

    def open(self, page: Path) -> None:
        """Load ``page`` from file:// and wait until its script has drawn it."""
        from selenium.webdriver.support.ui import WebDriverWait
        self.driver.get(page.resolve().as_uri())
        WebDriverWait(self.driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready"))

    def quit(self) -> None:
        self.driver.quit()
        shutil.rmtree(self.profile, ignore_errors=True)
