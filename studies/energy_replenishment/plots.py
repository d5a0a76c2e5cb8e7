"""The seed's Figures 9-12 from sweep results (:func:`sweep.load`), as deterministic PNGs, and
the summary table behind docs/studies/energy-replenishment.md.

Figure 9: heat maps over chargers n_m x capacity ratio phi (the fixed strategy in the 0 x 0
cell) of (a) work, (b) total energy spent (consumed and lost), (c) efficiency, (d) depleted
workers, each cell the mean over its trials. Figures 10-12: (a) work and (b) efficiency of both
strategies against the workload ratio, the charging rate and the transfer loss: every trial as a
dot, the mean as a diamond on the line, ±1 standard deviation as a band. Efficiency is a per
cent in every figure; each figure says so, and what its marks mean, in its legend and caption
(:func:`..plotting.save`)."""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional, Tuple

import numpy as np

from ...boundary.output import write_outputs
from ..plotting import pyplot, save
from .params import Params
from .sweep import load

COLOURS = {"fixed": "#1b9e77", "mobile": "#7570b3"}
DEFAULT = Params()

# The captions the PNGs carry and docs/studies/energy-replenishment.md prints under each figure.
FIGURE9_CAPTION = (
    "Figure 9: fixed chargers (column n_m = 0, capacity ratio 0) and n_m mobile chargers of capacity ratio "
    "phi = c_m,max / c_w,max (6 workers). Each cell is the mean over its %s trials of: (a) work done "
    "(units, one per 0.1-s step of working); (b) total energy spent, consumed and lost in transfers (energy "
    "units); (c) energy efficiency, per cent (energy spent working / energy spent and lost); (d) depleted "
    "workers (of 6). The colour scale is per panel.")
LINES_CAPTION = (
    "%(title)s: (a) work done (units, one per 0.1-s step of working) and (b) energy efficiency (per cent) "
    "against the %(x)s, for fixed chargers (green) and 6 mobile chargers of twice the workers' capacity "
    "(purple), %(runs)s trials per point. Dot: one trial; diamond on the line: the mean of the trials at "
    "that value; band: the mean ± 1 standard deviation.")
# Each file's caption template (the figures' page prints them filled in).
CAPTIONS = {"energy_fig9.png": FIGURE9_CAPTION, "energy_fig10.png": LINES_CAPTION, "energy_fig11.png": LINES_CAPTION,
            "energy_fig12.png": LINES_CAPTION}


def _spent(trials):
    return trials["consumed"] + trials["lost"]


def _at_base(trials, base: Params, **except_these):
    """Trials whose rates are the sweep's base rates (``base``: what `sweep energy` was given),
    except the columns named."""
    keep = np.ones(len(trials), dtype=bool)
    for column in ("work_rate", "move_rate", "core_rate", "charge_rate", "transfer_rate", "transfer_loss", "capacity",
                   "workers", "duration_s", "strip_inset_m"):
        if column not in except_these and column in trials:     # results from before a field had the default
            keep &= np.isclose(trials[column], getattr(base, column))
    return trials[keep]


def figure9(plt, trials, base: Params, path: Path) -> Optional[Path]:
    """Figure 9, or None without trials at the base rates."""
    rows = _at_base(trials, base).copy()
    if rows.empty:
        return None
    rows["phi"] = np.where(rows["strategy"] == "fixed", 0.0, rows["charger_capacity"] / rows["capacity"])
    rows["n_m"] = np.where(rows["strategy"] == "fixed", 0, rows["chargers"])
    rows["spent"] = _spent(rows)
    rows["efficiency_pct"] = 100 * rows["efficiency"]
    panels = (("work", "(a) work (units)", "%.0f"), ("spent", "(b) total energy spent (energy units)", "%.0f"),
              ("efficiency_pct", "(c) energy efficiency (%)", "%.1f"), ("depleted", "(d) depleted workers", "%.2f"))
    figure, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for axis, (column, title, fmt) in zip(axes.flat, panels):
        table = rows.groupby(["phi", "n_m"])[column].mean().unstack("n_m")
        image = axis.imshow(table.values, origin="lower", cmap="viridis", aspect="auto")
        axis.set_xticks(range(len(table.columns)), [str(int(c)) for c in table.columns])
        axis.set_yticks(range(len(table.index)), ["%g" % v for v in table.index])
        axis.set_xlabel("mobile chargers n_m (0: fixed chargers)")
        axis.set_ylabel("charger capacity / worker capacity")
        axis.set_title(title)
        for (i, j), value in np.ndenumerate(table.values):
            if not np.isnan(value):
                axis.text(j, i, fmt % value, ha="center", va="center", fontsize=6.5,
                          color="white" if value < np.nanmean(table.values) else "black")
        figure.colorbar(image, ax=axis)
    runs = rows.groupby(["phi", "n_m"]).size()
    figure.suptitle("Figure 9: number and capacity of mobile chargers (cell: mean of %s trials)" % _span(runs))
    return save(figure, path, FIGURE9_CAPTION % _span(runs))


def _span(counts) -> str:
    """``50`` or ``5-50``: how many trials the cells or points of a figure have."""
    low, high = int(counts.min()), int(counts.max())
    return "%d" % low if low == high else "%d-%d" % (low, high)


def _lines(plt, rows, column: str, xlabel: str, title: str, path: Path, log_x: bool = False,
           fixed_note: str = "") -> Path:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    figure, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    rows = rows.assign(efficiency_pct=100 * rows["efficiency"])
    for axis, (measure, label) in zip(axes, (("work", "(a) work (units)"), ("efficiency_pct", "(b) energy efficiency (%)"))):
        for strategy, group in rows.groupby("strategy"):
            stats = group.groupby(column)[measure].agg(["mean", "std"])
            x = stats.index.values
            axis.plot(group[column], group[measure], ".", alpha=0.25, color=COLOURS[strategy], markersize=3)
            axis.fill_between(x, stats["mean"] - stats["std"].fillna(0), stats["mean"] + stats["std"].fillna(0),
                              color=COLOURS[strategy], alpha=0.15)
            name = ("fixed chargers" + fixed_note) if strategy == "fixed" else "mobile chargers (6, 2x capacity)"
            axis.plot(x, stats["mean"], "-D", color=COLOURS[strategy], label=name, markersize=4)
        if log_x:
            axis.set_xscale("log", base=2)
        axis.set_xlabel(xlabel)
        axis.set_ylabel(label[4:])
        axis.set_title(label)
        axis.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(title="strategy")
    marks = [Line2D([], [], color="grey", marker=".", linestyle="", alpha=0.5, label="dot: one trial"),
             Line2D([], [], color="grey", marker="D", markersize=4, label="diamond: mean of the trials"),
             Patch(color="grey", alpha=0.15, label="band: mean ± 1 standard deviation")]
    axes[1].legend(handles=marks, title="marks (both panels)")
    runs = rows.groupby(["strategy", column]).size()
    figure.suptitle("%s (%s trials per point)" % (title, _span(runs)))
    return save(figure, path, LINES_CAPTION % dict(title=title, x=xlabel, runs=_span(runs)))


def _figure_rows(trials, base: Params, column: str):
    """Fixed chargers and mobile chargers (6, twice the workers' capacity) varying `column`."""
    rows = _at_base(trials, base, **{column: True, "transfer_rate": column == "charge_rate"})
    mobile = (rows["strategy"] == "mobile") & (rows["chargers"] == 6) & np.isclose(rows["charger_capacity"],
                                                                                  2 * rows["capacity"])
    return rows[(rows["strategy"] == "fixed") | mobile].copy()


def figure10(plt, trials, base: Params, path: Path) -> Optional[Path]:
    rows = _figure_rows(trials, base, "work_rate")
    if rows.empty:
        return None
    rows["ratio"] = rows["work_rate"] / rows["move_rate"]
    return _lines(plt, rows, "ratio", "workload ratio nu_work / nu_move", "Figure 10: workload", path, log_x=True)


def figure11(plt, trials, base: Params, path: Path) -> Optional[Path]:
    rows = _figure_rows(trials, base, "charge_rate")
    rows = rows[np.isclose(rows["charge_rate"], rows["transfer_rate"])].copy()
    if rows.empty:
        return None
    rows["per_step"] = rows["charge_rate"] / 10
    return _lines(plt, rows, "per_step", "charging = transfer rate (per 0.1-s step)", "Figure 11: charging rate", path)


def figure12(plt, trials, base: Params, path: Path) -> Optional[Path]:
    rows = _figure_rows(trials, base, "transfer_loss")
    if rows.empty:
        return None
    fixed = rows[rows["strategy"] == "fixed"]
    losses = sorted(rows.loc[rows["strategy"] == "mobile", "transfer_loss"].unique())
    import pandas as pd  # the fixed strategy has no transfers: its trials drawn at every loss
    rows = pd.concat([rows[rows["strategy"] == "mobile"]] + [fixed.assign(transfer_loss=x) for x in losses])
    return _lines(plt, rows, "transfer_loss", "transfer loss 1 - xi (fraction lost)", "Figure 12: transfer loss", path,
                  fixed_note=" (no transfers: drawn at every loss)")


def summarise(trials):
    """Means (and standard deviations) per configuration: the numbers of the reproduction page."""
    columns = ["work", "work_of_bound", "efficiency", "bound_efficiency", "depleted", "seconds"]
    keys = ["strategy", "chargers", "charger_capacity", "work_rate", "charge_rate", "transfer_loss"]
    grouped = trials.groupby(keys)
    table = grouped[columns].mean().join(grouped["work"].std().rename("work_std")).join(grouped.size().rename("runs"))
    return table.reset_index()


def draw_all(results, out, base: Params = DEFAULT) -> Tuple[List[Path], List[str]]:
    """The figures of the trials at ``base``'s rates (those of the sweep: a sweep at other
    rates than the defaults is drawn with the same rates) and the summary table; returns the
    files written and the figures left out for want of trials at those rates (a sweep of some
    figures only, or at other rates), rather than drawn empty."""
    plt = pyplot()
    trials = load(results)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths, missing = [], []
    for name, title, draw in (("energy_fig9.png", "Figure 9", figure9), ("energy_fig10.png", "Figure 10", figure10),
                              ("energy_fig11.png", "Figure 11", figure11), ("energy_fig12.png", "Figure 12", figure12)):
        path = draw(plt, trials, base, out / name)
        if path is None:
            missing.append(title)
        else:
            paths.append(path)
    summary = out / "energy_summary.csv"
    text = summarise(trials).to_csv(index=False, float_format="%.4f")
    write_outputs(out, {summary.name: (text.encode("utf-8"), False)})
    paths.append(summary)
    return paths, missing
