"""The seed's Figures 16-20 from sweep results (:func:`sweep.load`), as deterministic PNGs
(Agg backend, no timestamps in the files), each with its caption and its legends saying what
its marks, bands and shades mean (:func:`..plotting.save`)."""

from __future__ import annotations

from pathlib import Path
from typing import List, Tuple

import numpy as np

from ...boundary.escape import markdown
from ...boundary.output import write_outputs
from ..plotting import pyplot as _pyplot
from ..plotting import save as _save
from .metrics import winner_soh_map
from .sweep import load, summarise

COLOURS = {"least-confident": "#1b9e77", "most-confident": "#e7298a", "random": "#d95f02", "threshold": "#7570b3"}
MAP_SOCS = np.arange(10, 101, 10)
MAP_DISTANCES = np.arange(1000, 5001, 50)
MAP_MASSES = np.round(np.arange(0.5, 5.0001, 0.05), 2)

# The captions the PNGs carry and docs/studies/drone-delivery.md prints under each figure.
FIGURE16_CAPTION = (
    "%(title)s, %(runs)s runs per rule and mean inter-arrival time tau. (a) Delivered parcels "
    "against the median delivery time (min, log scale): each point is the median over the runs at one tau, "
    "labelled with that tau in minutes; its bars span the interquartile range of both quantities. "
    "(b) Aborted attempts, per cent of take-offs, per tau: box = quartiles of the runs, black line = median, "
    "whiskers to 1.5 x the interquartile range, circles = runs beyond. (c) Age of the orders still pending "
    "at the end (days, mean over the runs), stacked by the week they arrived: lighter shades are earlier "
    "weeks (legend: arrival week). Colours: the rules (legend of panel a).")
FIGURE17_CAPTION = (
    "Figure 17: fleet decision accuracy (per cent) at the end of each week (week 0: before the first "
    "order), tau = %(tau)g min, %(runs)s runs per rule. Line: the mean over drones and runs; band: its "
    "95 %% confidence interval (1.96 standard errors).")
FIGURE18_CAPTION = (
    "Figure 18: mean state of health (colour, 0.5-1) of the drone the least-confident rule deploys for a "
    "task of distance (m, x) and parcel mass (kg, y), one panel (a)-(j) per state of charge 10-100 %%, "
    "from the final policies of the %(runs)s runs at tau = %(tau)g min; white: no drone bids.")
FIGURE20_CAPTION = (
    "Figure 20: orders still pending at the end of the run, by the week they arrived, with and without reservation "
    "bids (forecasting), tau = %(tau)g min, after %(learned)s weeks of learning; each bar is the mean of "
    "%(runs)s runs.")
# Each file's caption template (the figures' pages print them filled in).
CAPTIONS = {"uav_fig16_rules.png": FIGURE16_CAPTION, "uav_fig17_accuracy.png": FIGURE17_CAPTION,
            "uav_fig18_soh_maps.png": FIGURE18_CAPTION, "uav_fig19_threshold.png": FIGURE16_CAPTION,
            "uav_fig20_forecast.png": FIGURE20_CAPTION}


def _label(trials):
    return np.where(trials["rule"] == "threshold", "threshold " + (100 * trials["threshold"]).round().astype(int).astype(str) + "%",
                    trials["rule"])


def _measured(trials):
    """Trials of the main grid (no forecasting experiment)."""
    return trials[(~trials["forecast"]) & (trials["pretrain_weeks"] == 0)]


def figure16(plt, frames, path: Path, groups, title: str) -> Path:
    """(a) delivered vs median delivery time, (b) aborted attempts %, (c) backlog age by arrival week."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from matplotlib.ticker import ScalarFormatter
    trials = _measured(frames["trials"]).copy()
    trials["label"] = _label(trials)
    trials = trials[trials["label"].isin(groups)]
    figure, axes = plt.subplots(1, 3, figsize=(13, 4.4))
    taus = sorted(trials["tau_min"].unique())
    weeks = sorted(frames["backlog"][frames["backlog"]["key"].isin(trials["key"])]["arrival_week"].unique())
    shade = {week: 0.35 + 0.65 * (week + 1) / len(weeks) for week in weeks}
    for offset, label in enumerate(groups):
        rows = trials[trials["label"] == label]
        if rows.empty:
            continue
        colour = COLOURS.get(label) or plt.cm.Purples(0.35 + 0.1 * offset)
        stats = rows.groupby("tau_min")
        x = stats["median_delivery_min"].median()
        y = stats["delivered"].median()
        axes[0].errorbar(x, y, xerr=[x - stats["median_delivery_min"].quantile(0.25), stats["median_delivery_min"].quantile(0.75) - x],
                         yerr=[y - stats["delivered"].quantile(0.25), stats["delivered"].quantile(0.75) - y],
                         fmt="o-", color=colour, label=label, capsize=2, ms=3)
        for tau, px, py in zip(x.index, x.values, y.values):
            axes[0].annotate("%g" % tau, (px, py), textcoords="offset points", xytext=(3, 3), fontsize=6, color=colour)
        aborted = 100.0 * rows["aborted"] / rows["takeoffs"].where(rows["takeoffs"] > 0)
        axes[1].boxplot([aborted[rows["tau_min"] == t].dropna() for t in taus], positions=np.arange(len(taus)) * (len(groups) + 1) + offset,
                        widths=0.8, patch_artist=True, boxprops=dict(facecolor=colour), medianprops=dict(color="black"), flierprops=dict(ms=2))
        backlog = frames["backlog"][frames["backlog"]["key"].isin(rows["key"])].merge(rows[["key", "tau_min"]], on="key")
        table = backlog.groupby(["tau_min", "arrival_week"])["backlog_age_h"].mean().unstack(fill_value=0.0) / 24.0
        bottom = np.zeros(len(table))
        positions = np.array([taus.index(t) for t in table.index]) * (len(groups) + 1) + offset
        for week in table.columns:
            axes[2].bar(positions, table[week].values, bottom=bottom, color=colour, edgecolor="white", width=0.8,
                        alpha=shade[week])
            bottom += table[week].values
    axes[0].set_xscale("log")
    axes[0].xaxis.set_major_formatter(ScalarFormatter())
    axes[0].set_xlabel("median delivery time (min)")
    axes[0].set_ylabel("delivered parcels")
    axes[0].set_title("(a) delivered against delivery time")
    marks = [Line2D([], [], color="grey", marker="o", ms=3, linestyle="", label="point: median of the runs"),
             Line2D([], [], color="grey", marker="|", ms=8, linestyle="-", label="bars: interquartile range"),
             Line2D([], [], color="none", label="number by a point: tau (min)")]
    axes[0].legend(handles=axes[0].get_legend_handles_labels()[0] + marks, fontsize=6.5, title="rule; marks")
    axes[1].legend(handles=[Patch(facecolor="grey", edgecolor="black", label="box: quartiles of the runs"),
                            Line2D([], [], color="black", label="line: median"),
                            Line2D([], [], color="black", marker="o", ms=2, linestyle="",
                                   label="circle: run beyond 1.5 x IQR")], fontsize=6.5)
    axes[2].legend(handles=[Patch(facecolor="grey", alpha=shade[w], label="week %d" % (w + 1)) for w in weeks],
                   fontsize=6, ncol=2, title="arrival week (shade)")
    for ax, letter, name in ((axes[1], "(b)", "aborted attempts (% of take-offs)"),
                             (axes[2], "(c)", "backlog age at the end (days)")):
        ax.set_xticks(np.arange(len(taus)) * (len(groups) + 1) + (len(groups) - 1) / 2)
        ax.set_xticklabels(["%g" % t for t in taus])
        ax.set_xlabel("mean inter-arrival time tau (min)")
        ax.set_ylabel(name)
        ax.set_title("%s %s" % (letter, name))
    figure.suptitle(title)
    return _save(figure, path, FIGURE16_CAPTION % dict(title=title, runs=_span(trials.groupby(["label", "tau_min"]).size())))


def _span(counts) -> str:
    """``20`` or ``5-20``: how many runs the points of a figure have."""
    low, high = int(counts.min()), int(counts.max())
    return "%d" % low if low == high else "%d-%d" % (low, high)


def figure17(plt, frames, path: Path, tau: float) -> Path:
    """Mean decision accuracy per week with a 95 % confidence interval (drones x runs)."""
    trials = _measured(frames["trials"])
    trials = trials[(trials["tau_min"] == tau) & (trials["rule"] != "threshold")]
    accuracy = frames["accuracy"].merge(trials[["key", "rule"]], on="key")
    figure, ax = plt.subplots(figsize=(5, 3.5))
    for rule, rows in accuracy.groupby("rule"):
        stats = rows.groupby("week")["accuracy"]
        mean, half = stats.mean(), 1.96 * stats.std(ddof=1).fillna(0.0) / np.sqrt(stats.count())
        ax.plot(mean.index, 100 * mean, color=COLOURS[rule], label="%s: mean" % rule)
        ax.fill_between(mean.index, 100 * (mean - half), 100 * (mean + half), color=COLOURS[rule], alpha=0.25,
                        label="%s: 95 %% confidence interval" % rule)
    ax.set_xlabel("week (0: before the first order)")
    ax.set_ylabel("decision accuracy (%)")
    ax.set_title("Figure 17: decision accuracy, tau = %g min" % tau)
    ax.legend(fontsize=6.5, title="rule: line, band")
    return _save(figure, path, FIGURE17_CAPTION % dict(tau=tau, runs=_span(trials.groupby("rule").size())))


def figure18(plt, frames, path: Path, tau: float) -> Path:
    """Mean SoH of the drone the least-confident rule deploys, per task and SoC."""
    trials = _measured(frames["trials"])
    keys = trials[(trials["tau_min"] == tau) & (trials["rule"] == "least-confident")]["key"]
    drones = frames["drones"][frames["drones"]["key"].isin(keys)]
    maps = [winner_soh_map(rows["soh"].values, rows[["w_distance", "w_mass", "w_soc"]].values, rows["intercept"].values,
                           MAP_SOCS, MAP_DISTANCES, MAP_MASSES)
            for _, rows in drones.groupby("key")]
    figure, axes = plt.subplots(2, 5, figsize=(12, 5), sharex=True, sharey=True, layout="constrained")
    if maps:
        with np.errstate(invalid="ignore"):
            import warnings
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                mean = np.nanmean(np.stack(maps), axis=0)
        for index, ax in enumerate(axes.ravel()):
            image = ax.imshow(mean[index].T, origin="lower", aspect="auto", cmap="coolwarm", vmin=0.5, vmax=1.0,
                              extent=(MAP_DISTANCES[0], MAP_DISTANCES[-1], MAP_MASSES[0], MAP_MASSES[-1]))
            ax.set_title("(%s) SoC %d %%" % ("abcdefghij"[index], MAP_SOCS[index]))
            ax.set_xticks([1000, 3000, 5000])
        figure.colorbar(image, ax=axes.ravel().tolist(), label="mean SoH of the winner (white: no drone bids)")
    for ax in axes[1]:
        ax.set_xlabel("distance (m)")
    for ax in axes[:, 0]:
        ax.set_ylabel("mass (kg)")
    figure.suptitle("Figure 18: the drone the least-confident rule deploys, tau = %g min" % tau)
    return _save(figure, path, FIGURE18_CAPTION % dict(tau=tau, runs=len(maps)), tight=False)


def figure20(plt, frames, path: Path, tau: float) -> Path:
    """Pending orders after the run by arrival week, with and without reservations."""
    trials = frames["trials"]
    trials = trials[(trials["pretrain_weeks"] > 0) & (trials["tau_min"] == tau)]
    backlog = frames["backlog"].merge(trials[["key", "forecast"]], on="key")
    figure, ax = plt.subplots(figsize=(5, 3.5))
    for shift, (forecast, rows) in enumerate(sorted(backlog.groupby("forecast"), key=lambda item: item[0])):
        mean = rows.groupby("arrival_week")["pending"].mean()
        ax.bar(mean.index + 1 + (shift - 0.5) * 0.4, mean.values, width=0.4,
               label="with reservations" if forecast else "without", color="#66a61e" if forecast else "#a6761d")
    ax.set_xlabel("arrival week")
    ax.set_ylabel("pending orders at the end (mean of the runs)")
    learned = ", ".join(str(w) for w in sorted(trials["pretrain_weeks"].unique()))
    ax.set_title("Figure 20: tau = %g min, after %s weeks of learning" % (tau, learned))
    ax.legend(title="bar: mean of the runs")
    runs = _span(trials.groupby("forecast").size())
    return _save(figure, path, FIGURE20_CAPTION % dict(tau=tau, learned=learned, runs=runs))


def summary_markdown(frames) -> str:
    """Medians per configuration as a Markdown table (the reproduction page's numbers)."""
    table = summarise(dict(frames, trials=_measured(frames["trials"])))
    lines = ["| rule | tau (min) | runs | delivered | pending | aborted (% of take-offs) | median delivery (min) | final accuracy (%) |",
             "|---|---|---|---|---|---|---|---|"]
    for row in table.sort_values(["rule", "threshold", "tau_min"]).itertuples():
        # (markdown: a rule's name comes from the trials' tables, files a user may have edited)
        rule = markdown(row.rule) if row.rule != "threshold" else "threshold %d %%" % round(100 * row.threshold)
        lines.append("| %s | %g | %d | %.0f | %.0f | %.0f (%.1f %%) | %.1f | %.1f |" % (
            rule, row.tau_min, row.runs, row.delivered, row.pending, row.aborted, row.aborted_pct,
            row.median_delivery_min, 100 * row.final_accuracy))
    return "\n".join(lines) + "\n"


def draw_all(results, out, tau: float = 20.0) -> Tuple[List[Path], List[str]]:
    """Every figure the results allow, into ``out``; returns the files written and what is left
    out for want of trials at ``tau`` (Figures 17, 18 and 20 are drawn at one inter-arrival
    mean: at a tau the sweep did not run they would be empty)."""
    frames = load(results)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    plt = _pyplot()
    written: List[Path] = []
    missing: List[str] = []
    trials = frames["trials"]
    if trials.empty:
        return written, missing
    measured = _measured(trials)
    labels = set(_label(measured))
    at_tau = set(_label(measured[np.isclose(measured["tau_min"], tau)]))
    swept = ", ".join("%g" % t for t in sorted(trials["tau_min"].unique()))

    def at(title: str, present: bool) -> bool:
        """Whether a figure at tau has trials; if not, it is named in ``missing``."""
        if not present:
            missing.append("%s: no trials at tau %g min (the sweep's: %s)" % (title, tau, swept))
        return present

    learning = [r for r in ("least-confident", "most-confident", "random") if r in labels]
    if learning:
        written.append(figure16(plt, frames, out / "uav_fig16_rules.png", learning, "Figure 16: winner rules"))
        if at("Figure 17", bool(at_tau & set(learning))):
            written.append(figure17(plt, frames, out / "uav_fig17_accuracy.png", tau))
    if "least-confident" in labels and at("Figure 18", "least-confident" in at_tau):
        written.append(figure18(plt, frames, out / "uav_fig18_soh_maps.png", tau))
    thresholds = sorted((label for label in labels if label.startswith("threshold")),
                        key=lambda label: abs(int(label[10:-1]) - 80))
    if thresholds and "least-confident" in labels:       # against the best threshold of the seed, 80 %
        written.append(figure16(plt, frames, out / "uav_fig19_threshold.png", ["least-confident", thresholds[0]],
                                "Figure 19: learning (least confident) against the threshold rule"))
    pretrained = trials[trials["pretrain_weeks"] > 0]
    if not pretrained.empty and at("Figure 20", bool(np.isclose(pretrained["tau_min"], tau).any())):
        written.append(figure20(plt, frames, out / "uav_fig20_forecast.png", tau))
    plt.close("all")
    summary = out / "uav_summary.md"
    write_outputs(out, {summary.name: (summary_markdown(frames).encode("utf-8"), False)})
    written.append(summary)
    return written, missing
