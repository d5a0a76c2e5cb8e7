"""The `--json FILE` of every benchmark: one option and one file shape, so that `make bench`'s
build/bench/*.json files (read by benchmarks/issue13.py's scorecard) are written alike."""

import argparse
import json
from pathlib import Path


def add_json_option(parser: argparse.ArgumentParser) -> None:
    """The benchmark's `--json FILE` option."""
    parser.add_argument("--json", metavar="FILE", help="also write the figures to this file")


def write_figures(path: str | None, figures: object) -> None:
    """The figures as JSON in ``path`` (its folder made), keys sorted; nothing without ``--json``."""
    if path is None:
        return
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(figures, indent=1, sort_keys=True) + "\n")
