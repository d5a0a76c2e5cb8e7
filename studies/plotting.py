"""Matplotlib set-up the studies' figures share: the Agg backend and deterministic PNGs (no
timestamps or software tags in the files, a fixed hash salt)."""

from __future__ import annotations

from pathlib import Path


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 8, "svg.hashsalt": "swarmvm"})
    return plt


def save(figure, path: Path) -> Path:
    figure.tight_layout()
    figure.savefig(str(path), dpi=110, metadata={"Software": None})
    figure.clf()
    return path
