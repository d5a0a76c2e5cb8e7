"""`swarmvm footprint --chart FILE.svg` (docs/footprint.md, "Formats"): well-formed SVG with one
bar group per row, each bar split into VM core, tables and application, a stack bar and a cycles
bar where measured, the budget and limit marked; against a baseline its bar above each; a row
over a budget or limit marked; one scale per target; the same report gives the same bytes; a
name holding markup cannot break the file, nor the Markdown and JUnit reports. Before this
change there was no --chart (usage error); before issue 36, point 3, no baseline bars, no stack
or cycles, no over-budget mark, and one scale for every target."""

import xml.etree.ElementTree as ET

from footprint_images import elf, swarmvm_footprint
from swarmvm.footprint import budget, chart as fp_chart, delta, measure as footprint, report
from swarmvm.footprint.cycles import Cycles
from swarmvm.footprint.measure import Footprint, Split
from swarmvm.footprint.stack import Stack

PARTS = ("core", "tables", "application")

SVG = "{http://www.w3.org/2000/svg}"


def chart(*args, path, cwd=None):
    result = swarmvm_footprint(*args, "--chart", path, cwd=cwd)
    assert result.returncode in (0, 1), result.stderr
    return ET.parse(path).getroot()


def groups(root):
    return {g.get("data-row"): g for g in root.iter(SVG + "g") if g.get("class") == "row"}


def test_one_bar_group_per_row_with_its_split_budget_and_limit(build, larger, tmp_path):
    budget = tmp_path / "budget.toml"
    budget.write_text("[kilobot]\nflash = 12000\n")
    images = [elf(build, "capbot", "energy_worker"), elf(build, "kilobot", "network_worker"), larger]
    root = chart(*images, "--budget", budget, path=tmp_path / "f.svg")
    rows = groups(root)
    assert sorted(rows) == ["capbot/energy_worker", "kilobot/energy_worker", "kilobot/network_worker"]
    paths = dict(zip(["capbot/energy_worker", "kilobot/network_worker", "kilobot/energy_worker"], images))
    for name, group in rows.items():
        parts = [r.get("class") for r in group.iter(SVG + "rect") if r.get("class") in PARTS + ("stack",)]
        known = "unknown" not in [t.text for t in group.iter(SVG + "text")]        # flash and RAM are known
        assert parts == ["core", "tables", "application"] * 2 + ["stack"] * known   # flash, RAM, stack (if known)
        lines = sorted(line.get("class") for line in group.iter(SVG + "line"))
        kilobot = name.startswith("kilobot/")
        # both: the flash, RAM and SRAM (stack) limits of the robot's record; the Kilobot: the flash budget too
        assert lines == (["budget", "limit", "limit", "limit"] if kilobot else ["limit", "limit", "limit"])
        over = kilobot and (footprint.measure(paths[name]).flash.total > 12000 or not known)   # budget, SRAM limit
        assert (group.get("data-over") == "true") == over
    measured = footprint.measure(larger)
    rects = [r for r in rows["kilobot/energy_worker"].iter(SVG + "rect") if r.get("class") in PARTS]
    widths = [float(r.get("width")) for r in rects[:3]]
    # the flash bar's parts are in the proportions of the measured split
    assert abs(widths[0] / sum(widths) - measured.flash.core / measured.flash.total) < 0.01
    budget_line = next(line for line in rows["kilobot/energy_worker"].iter(SVG + "line") if line.get("class") == "budget")
    start = float(rects[0].get("x"))
    assert abs((float(budget_line.get("x1")) - start) / sum(widths) - 12000 / measured.flash.total) < 0.01


def test_the_same_report_gives_the_same_bytes(build, tmp_path):
    images = [elf(build, "kilobot", "energy_worker"), elf(build, "capbot", "network_worker")]
    for name in ("a.svg", "b.svg"):
        assert swarmvm_footprint(*images, "--chart", tmp_path / name).returncode == 0
    assert (tmp_path / "a.svg").read_bytes() == (tmp_path / "b.svg").read_bytes()


def test_a_name_with_markup_cannot_break_the_chart_or_the_reports(build, tmp_path):
    """The supervisor's name is the ELF's: `<b>&"x'|*.elf` reaches the SVG as text, the JUnit XML
    as an attribute and the Markdown as a cell, each escaped for its context. Run away from the
    checkout: its pyproject.toml budgets a row energy_worker, which no image of this run is."""
    name = "<b>&\"x'|*"
    image = tmp_path / (name + ".elf")
    image.write_bytes(elf(build, "kilobot", "energy_worker").read_bytes())
    root = chart(image, path=tmp_path / "f.svg", cwd=tmp_path)
    assert list(groups(root)) == ["kilobot/" + name]
    assert [t.text for t in groups(root)["kilobot/" + name].iter(SVG + "text")][0] == "kilobot/" + name
    junit = swarmvm_footprint(image, "--format", "junit", "--kilobot-flash", "10", cwd=tmp_path)
    cases = ET.fromstring(junit.stdout).findall(".//testcase")
    assert {c.get("classname") for c in cases} == {"kilobot/" + name}
    assert cases[0].find("failure").text.startswith("kilobot/%s: flash " % name)
    markdown = swarmvm_footprint(image, cwd=tmp_path).stdout
    assert "| kilobot | \\<b\\>&\"x'\\|\\* | " in markdown


def test_a_chart_onto_a_folder_is_one_line_before_any_output(build, tmp_path):
    folder = tmp_path / "chart.svg"
    folder.mkdir()
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), "--chart", folder)
    assert result.returncode == 2 and result.stdout == "" and result.stderr == (
        "swarmvm: error: %s: --chart: is a folder, not a file that can be written\n" % folder)


def test_json_and_chart_are_one_transaction(build, tmp_path):
    """Both written, or neither: a chart that cannot be written leaves no JSON behind (before,
    the JSON was written first and stayed), and an old JSON keeps its bytes."""
    folder = tmp_path / "charts" / "chart.svg"
    folder.mkdir(parents=True)
    report = tmp_path / "report.json"
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), "--json", report, "--chart", folder)
    assert result.returncode == 2 and result.stdout == "" and result.stderr == (
        "swarmvm: error: %s: --json, --chart: is a folder, not a file that can be written\n" % folder)
    assert not report.exists()
    report.write_text("old\n")
    assert swarmvm_footprint(elf(build, "kilobot", "energy_worker"), "--json", report, "--chart", folder).returncode == 2
    assert report.read_text() == "old\n"
    both = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), "--json", report, "--chart", tmp_path / "c.svg")
    assert both.returncode == 0 and report.read_text().startswith("{") and (tmp_path / "c.svg").is_file()


def test_no_budget_or_limit_line_strikes_a_value_label(build, tmp_path):
    """A budget just above the figure put its line across the label written after the bar
    (issue 36, point 7): the labels are now in a column of their own, right of every line."""
    image = elf(build, "kilobot", "energy_worker")
    measured = footprint.measure(image)
    budget_file = tmp_path / "budget.toml"
    budget_file.write_text("[kilobot]\nflash = %d\nram = %d\n" % (measured.flash.total + 400, measured.ram.total + 20))
    (group,) = groups(chart(image, "--budget", budget_file, path=tmp_path / "f.svg", cwd=tmp_path)).values()
    labels = [t for t in group.iter(SVG + "text") if t.text and t.text.isdigit()]
    assert [t.text for t in labels][:2] == [str(measured.flash.total), str(measured.ram.total)] and len(labels) == 3
    for line in group.iter(SVG + "line"):
        at = float(line.get("x1"))
        for label in labels:
            start = float(label.get("x"))
            assert not start - 2 <= at <= start + 7.5 * len(label.text), (line.get("class"), at, start)


def image(target, name, flash, ram, stack=None, cycles=None, unknown=None):
    """A row measured in memory (no ELF): flash and RAM split 1:1:2 into core, tables, application."""
    made = Footprint(target, name, name + ".elf", Split(flash, flash // 4, flash // 4, flash - flash // 2),
                     Split(ram, ram // 4, 0, ram - ram // 4))
    if stack is not None or unknown:
        made.stack = Stack(10, stack, {"total": unknown} if unknown else {})
    if cycles is not None:
        made.cycles = Cycles("events.txt", tuple(cycles), ("a",), "d" * 64)
    return made


def test_baseline_bars_stack_and_cycles_over_marks_and_one_scale_per_target(tmp_path):
    """In memory: a CapBot row ten times the Kilobot's is drawn on its own scale, its largest
    figure (its flash limit) the panel's width, as the Kilobot's is on its; a baseline's bars stand above the bars now
    (a removed row has only its own); stack and cycles bars are drawn, an unknown stack labelled
    and, over a budget, its row marked."""
    old = tmp_path / "old.json"
    old.write_text(report.json_report(report.build(
        [image("kilobot", "a", 8000, 200, 100, [900, 1100]), image("kilobot", "gone", 4000, 100, 90, [800]),
         image("capbot", "a", 80000, 20000, 300, [500])], footprint.Limits(), budget.Budgets())))
    budgets = budget.parse_budgets("budget.toml", {"kilobot": {"stack": 150}})
    now = report.build([image("kilobot", "a", 9000, 210, unknown="indirect call in f", cycles=[950, 1200]),
                        image("capbot", "a", 80000, 20000, 300, [500])],
                       footprint.Limits(), budgets, delta.read_baseline(str(old)))
    root = ET.fromstring(fp_chart.svg_chart(now))
    rows = groups(root)
    assert sorted(rows) == ["capbot/a", "kilobot/a", "kilobot/gone"]
    headings = [t.text for t in root.iter(SVG + "text") if t.get("class") == "target"]
    assert headings == ["capbot (its own scale)", "kilobot (its own scale)"]
    kilobot = rows["kilobot/a"]
    classes = [r.get("class") for r in kilobot.iter(SVG + "rect")]
    assert classes.count("before") == 4 and "cycles" in classes and "stack" not in classes      # stack unknown now
    assert kilobot.get("data-over") == "true"                                 # its stack budget cannot be checked
    texts = [t.text for t in kilobot.iter(SVG + "text")]
    assert "unknown (was 100)" in texts and "9000 (+1000)" in texts and "1200 (+100)" in texts
    assert [r.get("class") for r in rows["kilobot/gone"].iter(SVG + "rect")] == ["before"] * 4
    assert "removed" in [t.text for t in rows["kilobot/gone"].iter(SVG + "text")]

    def flash_width(group):
        return sum(float(r.get("width")) for r in group.iter(SVG + "rect") if r.get("class") in PARTS[:3]
                   and float(r.get("x")) < fp_chart._x(1))
    for row, flash in ((rows["capbot/a"], 80000), (kilobot, 9000)):                  # each on its robot's flash limit
        limit = footprint.Limits().robots[row.get("data-row").split("/")[0]].flash
        assert abs(flash_width(row) - fp_chart.PANEL_WIDTH * flash / limit) < 0.5
