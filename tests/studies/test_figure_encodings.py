"""Issue 27: every figure the studies draw states its encodings. Each figure is drawn from small
made-up or quick results and its PNG read back: the caption (``Description``) and the texts it
shows (``Texts``: titles, axis labels, legends, annotations) must say what the marks, bands and
shades mean, the units, and the panel letters; the studies' pages print each caption under its
figure. Before, Figures 10-12 did not say what the diamond and the band were, efficiency was a
fraction there and a per cent in Figure 9, Figures 16a/19a did not label their points by tau,
panels had no letters, and the week shading of 16c/19c had no legend."""

import re
from pathlib import Path

import pytest

from swarmvm.studies import sweeps
from swarmvm.studies.drone_delivery import plots as uav_plots
from swarmvm.studies.drone_delivery import sweep as uav_sweep
from swarmvm.studies.drone_delivery.params import Params as UavParams
from swarmvm.studies.energy_replenishment import plots as energy_plots
from swarmvm.studies.energy_replenishment import sweep as energy_sweep
from swarmvm.studies.energy_replenishment.params import Params as EnergyParams
from swarmvm.studies.plotting import read_encodings

DOCS = Path(__file__).resolve().parents[2] / "docs" / "studies"
LINE_MARKS = ["dot: one trial", "diamond: mean of the trials", "band: mean ± 1 standard deviation"]


@pytest.fixture(scope="module")
def energy_figures(tmp_path_factory):
    """Every energy figure from made-up trials (the drawing is under test, not ARGoS)."""
    folder = tmp_path_factory.mktemp("energy")
    base = EnergyParams(duration_s=30.0)
    for p in energy_sweep.grid(base, seeds=[1, 2]):
        row = dict(key=energy_sweep.trial_key(p), **p.to_dict(), work=100.0 * p.work_rate + p.seed, efficiency=0.5,
                   depleted=0.0, consumed=50.0, lost=1.0, work_of_bound=0.9, bound_efficiency=0.7, seconds=1.0)
        sweeps.write_trial(folder / "grid", row["key"], dict(trials=[row]), energy_sweep.TABLES)
    paths, missing = energy_plots.draw_all(folder / "grid", folder / "img", base)
    assert missing == []
    return {p.name: read_encodings(p) for p in paths if p.suffix == ".png"}


@pytest.fixture(scope="module")
def uav_figures(tmp_path_factory):
    """Every drone figure from quick trials: two taus, a threshold, the forecasting variant."""
    folder = tmp_path_factory.mktemp("uav")
    base = UavParams(weeks=2, week_s=3000, drones=5, accuracy_samples=20)
    specs = uav_sweep.grid(base, rules=["least-confident", "random"], thresholds=[0.8], taus=[10, 20], seeds=[1])
    specs += [base.replace(pretrain_weeks=1, forecast=f, tau_min=20.0) for f in (False, True)]
    uav_sweep.sweep(specs, folder / "grid", progress=False)
    paths, missing = uav_plots.draw_all(folder / "grid", folder / "img")
    assert missing == []
    return {p.name: read_encodings(p) for p in paths if p.suffix == ".png"}


def texts(encodings):
    return encodings["Texts"].splitlines()


def test_energy_figure9_states_cells_units_and_panels(energy_figures):
    figure = energy_figures["energy_fig9.png"]
    assert "mean over its 2 trials" in figure["Description"]
    assert {"(a) work (units)", "(b) total energy spent (energy units)", "(c) energy efficiency (%)",
            "(d) depleted workers"} <= set(texts(figure))


@pytest.mark.parametrize("name", ["energy_fig10.png", "energy_fig11.png", "energy_fig12.png"])
def test_energy_line_figures_state_the_diamond_the_band_and_per_cent(energy_figures, name):
    figure = energy_figures[name]
    assert set(LINE_MARKS) <= set(texts(figure))
    assert {"(a) work (units)", "(b) energy efficiency (%)", "energy efficiency (%)"} <= set(texts(figure))
    caption = figure["Description"]
    assert "diamond on the line: the mean" in caption and "band: the mean ± 1 standard deviation" in caption
    assert "efficiency (per cent)" in caption and "2 trials per point" in caption


def test_efficiency_is_a_per_cent_in_every_energy_figure(energy_figures):
    for name, figure in energy_figures.items():
        for text in texts(figure) + [figure["Description"]]:
            if "efficiency" in text:
                assert "%" in text or "per cent" in text, (name, text)


@pytest.mark.parametrize("name", ["uav_fig16_rules.png", "uav_fig19_threshold.png"])
def test_rule_figures_label_taus_shade_weeks_and_letter_panels(uav_figures, name):
    shown = texts(uav_figures[name])
    assert {"10", "20"} <= set(shown)                                   # the points of (a), labelled by tau
    assert {"point: median of the runs", "bars: interquartile range", "number by a point: tau (min)"} <= set(shown)
    assert {"box: quartiles of the runs", "line: median"} <= set(shown)
    assert {"arrival week (shade)", "week 1", "week 2"} <= set(shown)
    assert [t[:3] for t in shown if re.match(r"\([a-c]\) ", t)] == ["(a)", "(b)", "(c)"]
    assert "lighter shades are earlier weeks" in uav_figures[name]["Description"]


def test_accuracy_soh_and_forecast_figures_state_their_marks(uav_figures):
    accuracy = texts(uav_figures["uav_fig17_accuracy.png"])
    assert {"least-confident: mean", "least-confident: 95 % confidence interval"} <= set(accuracy)
    assert "Line: the mean over drones and runs; band: its 95 % confidence interval" in \
        uav_figures["uav_fig17_accuracy.png"]["Description"]
    maps = texts(uav_figures["uav_fig18_soh_maps.png"])
    assert [t for t in maps if re.match(r"\([a-j]\) SoC", t)] == [
        "(%s) SoC %d %%" % (letter, soc) for letter, soc in zip("abcdefghij", range(10, 101, 10))]
    assert "mean SoH of the winner (white: no drone bids)" in maps
    assert "bar: mean of the runs" in texts(uav_figures["uav_fig20_forecast.png"])


def caption_pattern(template: str) -> str:
    """A template's captions as a regular expression: its fields are anything."""
    parts = re.split(r"%(?:\(\w+\))?[sgd]", template.replace("%%", "\0"))
    return ".+".join(re.escape(part).replace("\0", "%") for part in parts)


@pytest.mark.parametrize("page,captions", [("energy-replenishment.md", energy_plots.CAPTIONS),
                                           ("drone-delivery.md", uav_plots.CAPTIONS)])
def test_the_pages_print_each_figures_caption(page, captions):
    """Every figure on a study's page is followed by the caption its plotting code writes."""
    lines = (DOCS / page).read_text().splitlines()
    shown = [(i, re.search(r"\]\((img/(?:grid/)?([\w.]+))\)", line)) for i, line in enumerate(lines)]
    shown = [(i, match.group(2)) for i, match in shown if match and match.group(2) in captions]
    assert shown
    for index, name in shown:
        caption = lines[index + 2] if index + 2 < len(lines) else ""
        assert re.fullmatch(r"\*%s\*" % caption_pattern(captions[name]), caption), (name, caption)
