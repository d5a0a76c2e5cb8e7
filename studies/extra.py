"""What the studies need beyond swarmvm: the ``studies`` extra of pyproject.toml, checked before
a study command imports it (a module of its own, which both command modules import)."""

from __future__ import annotations

import importlib.util

from ..boundary import terminal

# What `pip install "swarmvm[studies]"` adds (pyproject.toml), by import name.
STUDIES_EXTRA = ("numpy", "pandas", "pyarrow", "dask", "tqdm", "matplotlib")


def need_studies_extra() -> None:
    """Ends with one line and exit status 2 when the studies' dependencies are not installed
    (a plain `pip install swarmvm` leaves them out), instead of an ImportError traceback."""
    missing = [name for name in STUDIES_EXTRA if importlib.util.find_spec(name) is None]
    if missing:
        terminal.fail("the studies need %s: pip install \"swarmvm[studies]\"" % ", ".join(missing))
