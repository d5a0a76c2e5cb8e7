"""Deltas against a baseline, the Markdown and JUnit formats and --fail-on-growth
(docs/footprint.md, "Deltas against a baseline", "Formats"), on the real images and the Kilobot
energy_worker made larger (conftest.py).

Before this change the command had no --baseline, --format or --fail-on-growth (usage error,
status 2) and its JSON held no format version."""

import json
import re
import shlex
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from footprint_images import BALLAST_FLASH, BALLAST_RAM, elf, swarmvm_footprint
from swarmvm.footprint import measure as footprint

DOCS = Path(__file__).resolve().parents[2] / "docs" / "footprint.md"


@pytest.fixture(scope="module")
def baseline(build, tmp_path_factory):
    """The JSON report of the four images as built: the main branch's."""
    path = tmp_path_factory.mktemp("baseline") / "main.json"
    images = [elf(build, t, n) for t in ("capbot", "kilobot") for n in ("energy_worker", "network_worker")]
    result = swarmvm_footprint(*images, "--json", path)
    assert result.returncode == 0, result.stderr
    return path


def table_rows(markdown):
    """{(target, supervisor): [cells]} of the Markdown tables' rows."""
    rows = {}
    for line in markdown.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) > 3 and cells[0] in ("kilobot", "capbot"):
            rows[(cells[0], cells[1])] = cells[2:]
    return rows


def test_the_larger_image_shows_its_delta_in_bytes_and_per_cent(build, larger, baseline):
    before = footprint.measure(elf(build, "kilobot", "energy_worker"))
    after = footprint.measure(larger)
    grown = after.flash.total - before.flash.total
    assert grown >= BALLAST_FLASH and after.ram.total - before.ram.total == BALLAST_RAM
    result = swarmvm_footprint(larger, elf(build, "kilobot", "network_worker"), elf(build, "capbot", "energy_worker"),
                               elf(build, "capbot", "network_worker"), "--baseline", baseline)
    assert result.returncode == 0, result.stderr
    cells = table_rows(result.stdout)[("kilobot", "energy_worker")]
    assert cells[0] == "changed"
    assert cells[1] == "%d (was %d: +%d B, +%.2f %%)" % (after.flash.total, before.flash.total, grown,
                                                          100 * grown / before.flash.total)
    assert cells[5] == "%d (was %d: +%d B, +%.2f %%)" % (after.ram.total, before.ram.total, BALLAST_RAM,
                                                          100 * BALLAST_RAM / before.ram.total)
    assert cells[2] == str(after.flash.core)                     # the VM core did not change: no delta shown
    assert ("Against %s: 1 changed, 0 new, 0 removed, 3 unchanged; in total over the 4 rows in both: "
            "flash (+%d B, " % (baseline, grown)) in result.stdout


def test_new_and_removed_rows_and_the_summary_line(build, baseline, tmp_path):
    """A baseline of two Kilobot rows; the report has one of them and a CapBot row."""
    old = tmp_path / "old.json"
    assert swarmvm_footprint(elf(build, "kilobot", "energy_worker"), elf(build, "kilobot", "network_worker"),
                             "--json", old).returncode == 0
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), elf(build, "capbot", "energy_worker"),
                               "--baseline", old)
    assert result.returncode == 0, result.stderr
    rows = table_rows(result.stdout)
    assert rows[("capbot", "energy_worker")][0] == "new" and rows[("kilobot", "network_worker")][0] == "removed"
    removed = footprint.measure(elf(build, "kilobot", "network_worker"))
    assert rows[("kilobot", "network_worker")][1] == str(removed.flash.total)      # its old figures
    assert "Against %s: 0 changed, 1 new, 1 removed, 1 unchanged; in total over the 1 row in both: " \
           "flash (+0 B, +0.00 %%), RAM (+0 B, +0.00 %%)." % old in result.stdout


def test_changed_rows_come_first_and_unchanged_ones_are_folded(build, larger, baseline):
    result = swarmvm_footprint(elf(build, "capbot", "energy_worker"), larger, "--baseline", baseline)
    text = result.stdout
    changed = text.index("| kilobot | energy_worker | changed |")
    details = text.index("<details><summary>1 unchanged row</summary>")
    unchanged = text.index("| capbot | energy_worker | unchanged |")
    removed = text.index("| capbot | network_worker | removed |")
    assert changed < removed < details < unchanged < text.index("</details>")
    assert text.count("| target | supervisor | change |") == 2        # each table with its header


def test_without_a_baseline_the_table_is_todays(build):
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"))
    assert "unchanged row" not in result.stdout and "| change |" not in result.stdout    # (the checks fold too)
    assert "| target | supervisor | flash | VM core | tables | application | RAM | VM core | tables | application | VM |" \
        in result.stdout


def test_junit_has_a_testcase_per_row_and_check_and_the_failure(build, larger, baseline, tmp_path):
    budget = tmp_path / "budget.toml"
    bound = footprint.measure(elf(build, "kilobot", "energy_worker")).flash.total
    budget.write_text("[kilobot]\nflash = %d\n" % bound)
    result = swarmvm_footprint(larger, elf(build, "capbot", "energy_worker"), "--budget", budget,
                               "--format", "junit", "--baseline", baseline, "--fail-on-growth", "50")
    assert result.returncode == 1
    root = ET.fromstring(result.stdout)
    cases = root.findall("./testsuite/testcase")
    # each: flash, RAM, SRAM (stack) and VM limits, growth; kilobot: the flash budget too
    capbot_ram = footprint.measure(elf(build, "capbot", "energy_worker")).ram.total
    assert sorted((c.get("classname"), c.get("name")) for c in cases) == sorted([
        ("kilobot/energy_worker", "flash <= 28672 B (limit)"), ("kilobot/energy_worker", "ram <= 1024 B (limit)"),
        ("kilobot/energy_worker", "vm <= 100000 B (limit)"), ("kilobot/energy_worker", "flash <= %d B (budget)" % bound),
        ("kilobot/energy_worker", "stack <= %d B (limit)" % (2048 - footprint.measure(larger).ram.total)),
        ("kilobot/energy_worker", "growth <= 50 % per column"),
        ("capbot/energy_worker", "flash <= 995328 B (limit)"), ("capbot/energy_worker", "ram <= 260096 B (limit)"),
        ("capbot/energy_worker", "stack <= %d B (limit)" % (262144 - capbot_ram)),
        ("capbot/energy_worker", "vm <= 100000 B (limit)"), ("capbot/energy_worker", "growth <= 50 % per column")])
    failed = [c for c in cases if c.find("failure") is not None]
    assert len(failed) == 2                              # the flash budget, and RAM grew by over 50 %
    assert root.get("tests") == str(len(cases)) and root.find("testsuite").get("failures") == "2"
    budget_failure = next(c.find("failure") for c in failed if "budget" in c.get("name"))
    assert budget_failure.get("type") == "budget" and budget_failure.get("message").startswith(
        "flash %d B over its budget of %d B" % (footprint.measure(larger).flash.total, bound))
    growth = next(c.find("failure") for c in failed if "growth" in c.get("name"))
    assert growth.get("message").startswith("grew by more than 50 %: ram (+100 B, ")


def exact_baseline(larger, tmp_path, flash):
    """A baseline holding the larger image's own figures, but for its flash: ``flash``."""
    path = tmp_path / "exact.json"
    assert swarmvm_footprint(larger, "--json", path).returncode == 0
    data = json.loads(path.read_text())
    data["images"][0]["flash"]["total"] = flash
    path.write_text(json.dumps(data))
    return path


def test_fail_on_growth_passes_at_exactly_pct_and_fails_above(larger, tmp_path):
    """Flash 10,000 B in the baseline: the larger image's flash grew by exactly (flash - 10000) / 100
    per cent, a decimal with two digits that the comparison takes exactly."""
    flash = footprint.measure(larger).flash.total
    assert 10000 < flash < 20000
    pct = "%.2f" % ((flash - 10000) / 100)
    baseline = exact_baseline(larger, tmp_path, 10000)
    at = swarmvm_footprint(larger, "--baseline", baseline, "--fail-on-growth", pct)
    assert at.returncode == 0 and at.stderr == "", at.stderr
    below = "%.2f" % ((flash - 10000) / 100 - 0.01)
    above = swarmvm_footprint(larger, "--baseline", baseline, "--fail-on-growth", below)
    assert above.returncode == 1
    assert above.stderr == "swarmvm: footprint: kilobot/energy_worker: grew by more than %s %%: flash (+%d B, +%s %%)\n" \
        % (below, flash - 10000, pct)


def test_fail_on_growth_without_a_baseline_is_one_line():
    result = swarmvm_footprint("missing.elf", "--fail-on-growth", "5")
    assert result.returncode == 2 and result.stderr == (
        "swarmvm: error: --fail-on-growth: growth is measured against a --baseline: give one\n")


def test_a_figure_that_grew_from_zero_fails_any_growth_bound(larger, tmp_path):
    baseline = exact_baseline(larger, tmp_path, 0)
    result = swarmvm_footprint(larger, "--baseline", baseline, "--fail-on-growth", "1000000")
    assert result.returncode == 1 and "flash (+%d B, from 0)" % footprint.measure(larger).flash.total in result.stderr


def bad(data):
    return lambda report: json.dumps(data(report))


@pytest.mark.parametrize("content, key, message", [
    (lambda r: "{not json", "", "not a JSON file (Expecting property name"),
    (bad(lambda r: [1, 2]), "format", "not a swarmvm footprint report"),
    (bad(lambda r: {k: v for k, v in r.items() if k not in ("format", "version")}), "format",
     "not a swarmvm footprint report"),
    (bad(lambda r: dict(r, version=2)), "version", "a footprint report of version 2; this swarmvm reads version 1"),
    (bad(lambda r: dict(r, version="1")), "version", 'a footprint report of version "1"'),
    (bad(lambda r: dict(r, images={})), "images", "must be a list"),
    (bad(lambda r: dict(r, images=[7])), "images[0]", "must be an object"),
    (bad(lambda r: dict(r, images=[dict(r["images"][0], supervisor=None)])), "images[0].supervisor", "must be a string"),
    (bad(lambda r: dict(r, images=[dict(r["images"][0], vm="4 kB")])), "images[0].vm", "must be a whole number"),
    (bad(lambda r: dict(r, images=[dict(r["images"][0], flash=dict(r["images"][0]["flash"], core=-1))])),
     "images[0].flash.core", "must be a whole number"),
    (bad(lambda r: dict(r, images=r["images"] * 2)), "images[1]", "a second row kilobot/energy_worker"),
    (bad(lambda r: dict(r, images=[dict(r["images"][0], commit={"sha": 5})])), "images[0].commit.sha",
     "must be a string or null"),
    (bad(lambda r: dict(r, images=[dict(r["images"][0], sections={".text": {"kind": "flash", "size": 1,
                                                                            "symbols": {"f": -1}}})])),
     "images[0].sections..text.symbols.f", "must be a whole number"),
], ids=["not_json", "a_list", "no_format", "version_2", "version_text", "images_not_a_list", "image_not_an_object",
        "no_supervisor", "figure_text", "figure_negative", "row_twice", "commit_not_text", "symbol_size_negative"])
def test_a_baseline_that_is_not_a_report_of_this_version_is_one_line(build, content, key, message, tmp_path):
    report = tmp_path / "report.json"
    image = elf(build, "kilobot", "energy_worker")
    assert swarmvm_footprint(image, "--json", report).returncode == 0
    path = tmp_path / "baseline.json"
    path.write_text(content(json.loads(report.read_text())))
    result = swarmvm_footprint(image, "--baseline", path)
    assert result.returncode == 2 and result.stdout == "" and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.startswith("swarmvm: error: %s: %s" % (path, key + ": " if key else "")), result.stderr
    assert message in result.stderr


def test_two_images_of_the_same_row_are_one_line(build, tmp_path):
    copy = tmp_path / "energy_worker.elf"
    copy.write_bytes(elf(build, "kilobot", "energy_worker").read_bytes())
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), copy)
    assert result.returncode == 2 and result.stdout == "" and result.stderr.count("\n") == 1
    assert "a second kilobot image named energy_worker" in result.stderr


def docs_commands():
    """The pipeline commands of docs/footprint.md (the block after "In a pipeline")."""
    text = DOCS.read_text()
    block = re.search(r"In a pipeline.*?```\n(.*?)```", text, re.S).group(1).replace("\\\n", "")
    return [shlex.split(line.split("  #")[0]) for line in block.splitlines()]


def run_docs_command(words, image, cwd, build=None):
    """One documented command with the example's image replaced by ``image`` (and the network
    worker's by ``build``'s); ``> FILE`` done here."""
    images = {"build/kilobot/gen/energy_worker/energy_worker.elf": str(image)}
    if build is not None:
        images["build/kilobot/gen/network_worker/network_worker.elf"] = str(elf(build, "kilobot", "network_worker"))
    assert all(w in images for w in words if w.endswith(".elf")), words
    words = [images.get(w, w) for w in words]
    output = None
    if ">" in words:
        output = cwd / words[words.index(">") + 1]
        words = words[:words.index(">")]
    assert words[:2] == ["swarmvm", "footprint"]
    result = swarmvm_footprint(*words[2:], cwd=cwd)
    if output is not None:
        output.write_text(result.stdout)
    return result


def test_the_documented_pipeline_passes_the_same_image_and_catches_the_larger_one(build, larger, tmp_path):
    (tmp_path / "budget.toml").write_text(re.search(r"```toml\n(.*?)```", DOCS.read_text(), re.S).group(1)
                                          .replace("tool.swarmvm.footprint.", ""))
    keep, compare, junit = docs_commands()
    assert run_docs_command(keep, elf(build, "kilobot", "energy_worker"), tmp_path).returncode == 0
    assert json.loads((tmp_path / "footprint.json").read_text())["version"] == 1
    same = run_docs_command(compare, elf(build, "kilobot", "energy_worker"), tmp_path)
    assert same.returncode == 0 and (tmp_path / "footprint.svg").is_file(), same.stderr
    assert run_docs_command(junit, elf(build, "kilobot", "energy_worker"), tmp_path, build).returncode == 0
    grown = run_docs_command(compare, larger, tmp_path)
    assert grown.returncode == 1 and "grew by more than 5 %: " in grown.stderr
    assert "| ballast_flash (energy_worker_controller.c) | .text |" in grown.stdout      # --symbols 10
    over = run_docs_command(junit, larger, tmp_path, build)
    assert over.returncode == 1
    failures = ET.parse(tmp_path / "footprint-junit.xml").getroot().findall(".//failure")
    assert [f.get("type") for f in failures] == ["budget"] and "ram" in failures[0].get("message")
