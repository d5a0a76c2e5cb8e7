"""Matplotlib set-up the studies' figures share: the Agg backend, deterministic PNGs (no
timestamps or software tags in the files, a fixed hash salt), and figures that state their
encodings.

Every figure is saved with its caption — what each mark, band and shade means, the units, the
panels — in the PNG's ``Description`` text chunk, and every text the figure draws (titles, axis
labels, legend entries, annotations) in its ``Texts`` chunk, one per line: the reader's page
prints the same caption, and tests/studies/test_figure_encodings.py reads both back from files
drawn on small data."""

from __future__ import annotations

from pathlib import Path
from typing import Dict, List

CAPTION_KEY = "Description"
TEXTS_KEY = "Texts"


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 8, "svg.hashsalt": "swarmvm"})
    return plt


def figure_texts(figure) -> List[str]:
    from matplotlib.legend import Legend
    """Every non-empty text the figure shows: its title, and per panel the title, axis labels,
    annotations and legend (title and entries), colour bars included."""
    texts = [figure.get_suptitle()]
    legends = list(figure.legends)
    for axis in figure.axes:
        texts += [axis.get_title(), axis.get_xlabel(), axis.get_ylabel()]
        texts += [t.get_text() for t in axis.texts]
        legends += [a for a in axis.get_children() if isinstance(a, Legend)]
    for legend in legends:
        texts += [legend.get_title().get_text()] + [t.get_text() for t in legend.get_texts()]
    return [t for t in texts if t]


def save(figure, path: Path, caption: str, tight: bool = True) -> Path:
    """Writes the figure as a PNG carrying ``caption`` and the figure's texts (see above);
    ``tight``: lay it out first (a constrained layout lays itself out)."""
    if tight:
        figure.tight_layout()
    metadata = {"Software": None, CAPTION_KEY: caption, TEXTS_KEY: "\n".join(figure_texts(figure))}
    figure.savefig(str(path), dpi=110, metadata=metadata)
    from matplotlib import pyplot
    pyplot.close(figure)   # pyplot keeps every figure it made until closed
    return path


def read_encodings(path: Path) -> Dict[str, str]:
    """The caption and texts a PNG of :func:`save` carries (``Description``, ``Texts``)."""
    from PIL import Image
    with Image.open(path) as image:
        return {key: image.text.get(key, "") for key in (CAPTION_KEY, TEXTS_KEY)}
