"""One headless Chromium per module for the inspector's browser tests (tests/inspector/browser.py)."""

import os

import pytest


@pytest.fixture(scope="module")
def browser():
    from browser import Browser, missing
    why = missing()
    if why:
        if os.environ.get("CI") == "true":
            pytest.fail(why)
        pytest.skip(why)
    chromium = Browser()
    yield chromium
    chromium.quit()
