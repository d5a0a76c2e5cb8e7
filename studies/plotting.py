"""Matplotlib set-up the studies' figures share: the Agg backend, deterministic PNGs (no
timestamps or software tags in the files, a fixed hash salt), and figures that state their
encodings.

Every figure is saved with its caption — what each mark, band and shade means, the units, the
panels — in the PNG's ``Description`` text chunk, and every text the figure draws (titles, axis
labels, legend entries, annotations) in its ``Texts`` chunk, one per line: the reader's page
prints the same caption, and tests/studies/test_figure_encodings.py reads both back from files
drawn on small data."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Dict, List

from ..boundary.errors import read_input
from ..boundary.output import write_outputs

CAPTION_KEY = "Description"
FIGURE_MAX_BYTES = 64 << 20     # a study's PNG (the largest drawn is under 1 MB), read back by read_encodings
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
    ``tight``: lay it out first (a constrained layout lays itself out). Drawn in memory, then
    written through the output layer (swarmvm.boundary.output): the mode from the umask, no
    partial PNG on a failure, never over a link or an input (an InputError naming the file)."""
    if tight:
        figure.tight_layout()
    metadata = {"Software": None, CAPTION_KEY: caption, TEXTS_KEY: "\n".join(figure_texts(figure))}
    png = io.BytesIO()
    figure.savefig(png, format="png", dpi=110, metadata=metadata)
    from matplotlib import pyplot
    pyplot.close(figure)   # pyplot keeps every figure it made until closed
    path = Path(path)
    write_outputs(path.parent, {path.name: (png.getvalue(), False)})
    return path


def read_encodings(path: Path) -> Dict[str, str]:
    """The caption and texts a PNG of :func:`save` carries (``Description``, ``Texts``)."""
    from PIL import Image
    with Image.open(io.BytesIO(read_input(str(path), limit=FIGURE_MAX_BYTES))) as image:
        return {key: image.text.get(key, "") for key in (CAPTION_KEY, TEXTS_KEY)}
