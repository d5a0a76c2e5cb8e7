"""``swarmvm inspect`` writes one self-contained, deterministic HTML page (docs/inspect.md) whose
per-step data is the traces', whose user text cannot become markup or end its script, and which
refuses a trace of other supervisors in one line. (The browser's view: test_browser.py.)"""

import json
import re
import tomllib
from fnmatch import fnmatch
from html.parser import HTMLParser

import pytest

from inspect_cases import EXAMPLE, FLIPFLOP, NETWORK_WORKER, ROOT, swarmvm, trace_lines, write_trace
from swarmvm import api
from swarmvm.inspector import page as inspect_page
from swarmvm.boundary.escape import script_json
from swarmvm.inspector.encoding import decode
from swarmvm.inspector.page import ASSETS


class _Parts(HTMLParser):
    """The page's elements: tags with attributes, and the text of each <script>."""

    def __init__(self) -> None:
        super().__init__()
        self.tags, self.scripts, self._in_script = [], [], False

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag == "script":
            self._in_script = True
            self.scripts.append("")

    def handle_endtag(self, tag):
        self._in_script = self._in_script and tag != "script"

    def handle_data(self, data):
        if self._in_script:
            self.scripts[-1] += data


def parts(page: bytes) -> _Parts:
    parser = _Parts()
    parser.feed(page.decode())
    return parser


def data_of(page: bytes) -> dict:
    return json.loads(parts(page).scripts[0])


def test_the_page_is_one_file_that_fetches_nothing(tmp_path):
    traces = [str(write_trace(tmp_path, EXAMPLE, 50, seed, "robot%d.trace" % seed)) for seed in (1, 2)]
    out = tmp_path / "out"
    page = api.inspect(str(EXAMPLE), traces, str(out / "report.html"))
    assert [p.name for p in out.iterdir()] == ["report.html"] and page.path == str(out / "report.html")
    text = (out / "report.html").read_bytes()
    assert not re.search(rb"https?://|//[a-z0-9.-]+\.[a-z]{2,}/", text, re.I)     # no URL at all
    found = parts(text)
    assert all("src" not in attrs and "href" not in attrs for _tag, attrs in found.tags)
    assert [t for t, _ in found.tags].count("script") == 2 and ("link", {}) not in found.tags
    csp = [a["content"] for t, a in found.tags if t == "meta" and a.get("http-equiv") == "Content-Security-Policy"]
    assert csp and "default-src 'none'" in csp[0]
    assert text.count(b"<svg") == 4                                             # one drawing per supervisor


def test_the_same_inputs_give_the_same_bytes_without_paths(tmp_path):
    trace = str(write_trace(tmp_path, FLIPFLOP, 40, 3, "r.trace"))
    api.inspect(str(FLIPFLOP), [trace], str(tmp_path / "a.html"))
    api.inspect(str(FLIPFLOP), [trace], str(tmp_path / "b.html"))
    a = (tmp_path / "a.html").read_bytes()
    assert a == (tmp_path / "b.html").read_bytes()
    assert str(tmp_path).encode() not in a and str(ROOT).encode() not in a and b"graphviz version" not in a


@pytest.mark.parametrize("supervisor", [EXAMPLE, FLIPFLOP, NETWORK_WORKER], ids=lambda p: p.stem)
def test_each_step_holds_the_trace_line_and_the_enabled_events(supervisor, tmp_path):
    trace = write_trace(tmp_path, supervisor, 60, 7, "r.trace", density=0.4)
    api.inspect(str(supervisor), [str(trace)], str(tmp_path / "p.html"))
    data = data_of((tmp_path / "p.html").read_bytes())
    model = api.compile_model([str(supervisor)]).model
    steps = decode(data, data["runs"][0])
    assert steps[0] == ([0] * len(model.supervisors), [], 0)
    for step, events, states, violations in trace_lines(trace):
        assert steps[step] == (states, [model.events.index(e[3:]) for e in events], violations)
        enabled = [e for e, c in enumerate(model.controllable) if c and all(
            e in {t for t, _, _ in sup.states[states[s]]} for s, sup in enumerate(model.supervisors)
            if e in sup.alphabet)]
        assert data["enabled"][data["vectors"].index(states)] == enabled
    assert [kind for _name, kind, _public in data["events"]] == ["c" if c else "u" for c in model.controllable]


def test_lanes_are_sorted_naturally_and_the_simulator_has_every_transition(tmp_path):
    """Traces given in the shell's order (robot1, robot10, robot2) are lanes robot1, robot2,
    robot10 (two compared keep the order given); the simulator's tables are the model's, every
    transition of every state, so it can fire from vectors no trace reached."""
    traces = [str(write_trace(tmp_path, EXAMPLE, 5, seed, "robot%d.trace" % seed)) for seed in (1, 10, 2)]
    api.inspect(str(EXAMPLE), traces, str(tmp_path / "p.html"))
    data = data_of((tmp_path / "p.html").read_bytes())
    assert [r["name"] for r in data["runs"]] == ["robot1.trace", "robot2.trace", "robot10.trace"]
    assert inspect_page.natural_key("a2b9x") < inspect_page.natural_key("a2b10") < inspect_page.natural_key("a10")
    api.inspect(str(EXAMPLE), traces[1:], str(tmp_path / "c.html"), compare=True)
    assert [r["name"] for r in data_of((tmp_path / "c.html").read_bytes())["runs"]] == ["robot10.trace", "robot2.trace"]
    model = api.compile_model([str(EXAMPLE)]).model
    assert data["alphabets"] == [sorted(sup.alphabet) for sup in model.supervisors]
    assert data["tables"] == [[[[e, t] for e, t, _ in row] for row in sup.states] for sup in model.supervisors]
    assert data["source"] == EXAMPLE.name


@pytest.mark.parametrize("name", ["</script><script>window.pwned=1</script>", "<!--", "a & b <b>bold</b>",
                                  "\u2028</SCRIPT >"])
def test_user_text_stays_text(name, tmp_path):
    """The title, a trace's name and the supervisor file's (the simulator's replay command names
    it) are JSON data in the page, never markup."""
    supervisor = tmp_path / "<!--<script><b>.yaml"
    supervisor.write_bytes(EXAMPLE.read_bytes())
    trace = write_trace(tmp_path, EXAMPLE, 5, 1, "<script>.trace")
    api.inspect(str(supervisor), [str(trace)], str(tmp_path / "p.html"), name=name)
    page = (tmp_path / "p.html").read_bytes()
    found = parts(page)
    assert [t for t, _ in found.tags].count("script") == 2 and not any(t == "b" for t, _ in found.tags)
    data = json.loads(found.scripts[0])
    assert data["title"] == name and data["runs"][0]["name"] == "<script>.trace"
    assert data["source"] == supervisor.name
    assert len(re.findall(rb"</script", page, re.I)) == 2


def test_script_json_cannot_end_the_element():
    text = script_json({"k": "</script><!-- & \u2028"})
    assert "<" not in text and ">" not in text and "&" not in text and "\u2028" not in text
    assert json.loads(text) == {"k": "</script><!-- & \u2028"}


def test_the_page_assets_are_package_data_and_hold_no_end_tag():
    """The wheel carries templates/inspect/ (pyproject's package-data globs), and neither file
    could end the element it is inlined in."""
    globs = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    files = sorted(p.name for p in (ROOT / "templates" / "inspect").iterdir())
    assert files == sorted(ASSETS)
    for name in files:
        assert any(fnmatch("inspect/" + name, glob) for glob in globs["swarmvm.templates"]), name
        assert "</" not in inspect_page.asset(name)


@pytest.mark.parametrize("line,message", [
    ("1 EV_flip 0,1 0\n2 EV_nope 0,1 0", "line 2: EV_nope is not an event of the supervisors"),
    ("1 EV_flip 0 0", "line 1: 1 states for 2 supervisors"),
    ("1 EV_flip 0,9 0", "line 1: supervisor 1 has no state 9"),
    ("1 - 0,0 0\n3 - 0,0 0", "line 2: step 3 where step 2 was due"),
    ("1 - 0,0", "line 1: not STEP EVENTS STATES VIOLATIONS"),
    ("1 - 0,0 x", "line 1: violations x is not a number")])
def test_a_trace_of_other_supervisors_is_refused_in_one_line(line, message, tmp_path):
    (tmp_path / "bad.trace").write_text(line + "\n")
    run = swarmvm("inspect", str(FLIPFLOP), "bad.trace", "-o", "p.html", cwd=tmp_path)
    assert run.returncode == 2 and run.stderr == "swarmvm: error: bad.trace: trace: %s\n" % message
    assert not (tmp_path / "p.html").exists()


@pytest.mark.parametrize("end", ["\n", ""], ids=["with its newline", "last, without one"])
def test_a_line_over_the_limit_is_refused_however_the_file_is_cut(end, tmp_path, monkeypatch):
    """Read in blocks of 100 bytes, a line of 200 with the limit at 150: refused by its number,
    whether a newline ends it or the file does (it is not held on waiting for one)."""
    from swarmvm.inspector import trace
    monkeypatch.setattr(trace, "BLOCK", 100)
    monkeypatch.setattr(trace, "MAX_LINE_BYTES", 150)
    (tmp_path / "long.trace").write_text("1 - 0,0 0\n2 - 0,0 " + "0" * 190 + end)
    with pytest.raises(api.InputError) as error:
        api.inspect(str(FLIPFLOP), [str(tmp_path / "long.trace")], str(tmp_path / "p.html"))
    assert str(error.value) == "%s: line 2: line over the 150-byte limit" % (tmp_path / "long.trace")


def test_a_line_that_never_ends_is_not_held(tmp_path):
    """20 MB with no newline after line 1: refused at the limit, holding a block or two of it."""
    import tracemalloc
    (tmp_path / "endless.trace").write_bytes(b"1 - 0,0 0\n2 - " + b"0" * 20_000_000)
    tracemalloc.start()
    try:
        with pytest.raises(api.InputError, match="line 2: line over the"):
            api.inspect(str(FLIPFLOP), [str(tmp_path / "endless.trace")], str(tmp_path / "p.html"))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 8_000_000, peak


def test_compare_takes_exactly_two_traces(tmp_path):
    trace = write_trace(tmp_path, FLIPFLOP, 5, 1, "r.trace")
    run = swarmvm("inspect", str(FLIPFLOP), str(trace), "--compare", "-o", "p.html", cwd=tmp_path)
    assert run.returncode == 2 and run.stderr == "swarmvm: error: compare: compares exactly two traces, got 1\n"


def test_compare_finds_the_first_differing_step(tmp_path):
    a, b = write_trace(tmp_path, FLIPFLOP, 40, 1, "a.trace"), write_trace(tmp_path, FLIPFLOP, 40, 2, "b.trace")
    lines_a, lines_b = a.read_text().splitlines(), b.read_text().splitlines()
    expected = next(n for n, (x, y) in enumerate(zip(lines_a, lines_b), 1) if x != y)
    api.inspect(str(FLIPFLOP), [str(a), str(b)], str(tmp_path / "p.html"), compare=True)
    data = data_of((tmp_path / "p.html").read_bytes())
    assert data["compare"] is True and data["difference"] == expected
    api.inspect(str(FLIPFLOP), [str(a), str(a)], str(tmp_path / "same.html"), compare=True)
    assert data_of((tmp_path / "same.html").read_bytes())["difference"] is None


def test_a_page_over_the_limit_keeps_a_window_and_summarises_the_rest(tmp_path, monkeypatch):
    monkeypatch.setattr(inspect_page, "ROBOT_STEPS", 40)            # 2 traces: 20 steps each per page
    traces = [write_trace(tmp_path, FLIPFLOP, 50, seed, "r%d.trace" % seed) for seed in (1, 2)]
    page = api.inspect(str(FLIPFLOP), [str(t) for t in traces], str(tmp_path / "p.html"), first_step=21)
    assert (page.kept, page.total) == (40, 60)
    data = data_of((tmp_path / "p.html").read_bytes())
    for trace, run in zip(traces, data["runs"]):
        rows, steps = trace_lines(trace), decode(data, run)
        assert data["first"] == 21 and run["kept"] == 20 and len(steps) == 21 and run["steps"] == 50
        assert steps[0] == (rows[19][2], [], rows[19][3])                                  # before step 21
        assert [(s[0], s[2]) for s in steps[1:]] == [(r[2], r[3]) for r in rows[20:40]]  # steps 21 to 40
        assert data["vectors"][run["last"]] == rows[49][2] and run["lastViolations"] == rows[49][3]
        assert sum(run["counts"]) == sum(len(r[1]) for r in rows)


def test_the_command_says_where_the_next_page_starts(tmp_path, monkeypatch):
    from click.testing import CliRunner
    from swarmvm.cli.commands import main
    monkeypatch.setattr(inspect_page, "ROBOT_STEPS", 30)
    trace = write_trace(tmp_path, FLIPFLOP, 50, 1, "r.trace")
    result = CliRunner().invoke(main, ["inspect", str(FLIPFLOP), str(trace), "-o", str(tmp_path / "p.html")])
    assert result.exit_code == 0, result.output
    assert result.output.splitlines()[0] == str(tmp_path / "p.html")
    assert "30 of 50 robot-steps kept in full" in result.output and "--first-step 31" in result.output


def test_the_first_difference_is_looked_for_over_the_whole_runs(tmp_path, monkeypatch):
    """With --first-step past it, the first difference is still found (and the steps that differ
    counted), and the page knows the first difference among the steps it keeps."""
    monkeypatch.setattr(inspect_page, "ROBOT_STEPS", 40)            # 2 traces: 20 steps each per page
    a = write_trace(tmp_path, FLIPFLOP, 50, 1, "a.trace")
    rows = a.read_text().splitlines()
    changed = [line if n not in (5, 30) else line.rsplit(" ", 1)[0] + " 999" for n, line in enumerate(rows, 1)]
    (tmp_path / "b.trace").write_text("".join(line + "\n" for line in changed[:45]))
    traces = [str(a), str(tmp_path / "b.trace")]
    for first_step, shown in ((1, 5), (21, 30), (41, 46)):
        api.inspect(str(FLIPFLOP), traces, str(tmp_path / "p.html"), compare=True, first_step=first_step)
        data = data_of((tmp_path / "p.html").read_bytes())
        assert (data["difference"], data["differences"], data["differenceShown"]) == (5, 2 + 5, shown), first_step
    (tmp_path / "c.trace").write_text("".join(line + "\n" for line in changed[:29]))   # differs at 5, then ends
    api.inspect(str(FLIPFLOP), [str(a), str(tmp_path / "c.trace")], str(tmp_path / "p.html"), compare=True,
                first_step=21)
    data = data_of((tmp_path / "p.html").read_bytes())
    assert (data["difference"], data["differences"], data["differenceShown"]) == (5, 1 + 21, 30)
    b = write_trace(tmp_path, FLIPFLOP, 50, 1, "same.trace")
    api.inspect(str(FLIPFLOP), [str(a), str(b)], str(tmp_path / "p.html"), compare=True, first_step=41)
    data = data_of((tmp_path / "p.html").read_bytes())
    assert (data["difference"], data["differences"], data["differenceShown"]) == (None, 0, None)
