"""The inspector's page (docs/inspect.md): one self-contained HTML file replaying what a swarm's
VMs did against the supervisors they ran.

Everything is decided here, when the page is written, so the browser only displays: Graphviz
lays out each local supervisor (swarmvm.models.pictures' DOT, names already escaped there), every
distinct vector of states is numbered once with its enabled controllable events, and each run
becomes one small integer a step, packed (swarmvm.inspector.encoding: a table of the distinct
steps, and per run the base64 of its steps' rows), which the page decodes when it needs a run.
The supervisors' tables go in whole too, so that the page's simulator can fire any event from any
vector, not only those the traces reached, and so that the page walks the transitions a step
takes (every supervisor's, input by input, then the chosen event) with the simulator's own
firing; lanes are in natural order. The page carries its own script and style
(templates/inspect/, package data) and a Content-Security-Policy that allows no fetch at all: it
opens from ``file://`` offline, and the same inputs give the same bytes.

Size: a page keeps at most :data:`ROBOT_STEPS` steps of all runs together (200 robots of 100,000
steps, a page of about 54 MB); beyond, each run keeps the same window of steps from
``first_step`` and the page summarises the whole runs (length, last states, violations, events
counted): another ``--first-step`` pages through the rest."""

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from ..boundary.escape import html, script_json
from ..boundary.output import write_outputs
from ..compiler.model import Model
from ..compiler.runtime_files import TEMPLATES
from ..models.pictures import dot_to_svg, supervisor_dot
from ..models.product import Conjunction, events_of
from . import encoding
from .trace import Reading, read_runs

ROBOT_STEPS = 20_000_000
ASSETS = ("inspect.css", "inspect.js")
# What Graphviz writes before the <svg> element (XML prolog, DOCTYPE, comments) and the namespace
# attributes inline SVG does not need: gone, so the page holds no URL and no tool version.
_SVG_COMMENT = re.compile(r"<!--.*?-->", re.S)
_SVG_NAMESPACES = re.compile(r' xmlns(:xlink)?="[^"]*"')
_CSP = "default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src data:"


def window(runs: int) -> int:
    """Steps each of ``runs`` traces keeps in full on one page."""
    return max(1, ROBOT_STEPS // max(1, runs))


def inline_svg(svg: bytes) -> str:
    """Graphviz' SVG as an element of the page: from ``<svg`` on, without comments or namespaces."""
    text = svg.decode("utf-8")
    text = _SVG_COMMENT.sub("", text[text.index("<svg"):])
    return _SVG_NAMESPACES.sub("", text).strip()


def natural_key(name: str) -> list[tuple[int, int, str]]:
    """A lane's sort key: runs of digits compared as numbers, so robot2 comes before robot10
    (the shell's glob order puts robot10 first)."""
    return [(1, int(part), "") if part.isdigit() else (0, 0, part) for part in re.findall(r"\d+|\D+", name)]


def page_data(model: Model, title: str, reading: Reading, compare: bool) -> dict[str, object]:
    """Everything the page's script displays, as JSON-ready integers, names and packed runs
    (swarmvm.inspector.encoding). Lanes are sorted by :func:`natural_key`, except the two runs
    compared, which keep the order given (the first is drawn solid, the second dashed)."""
    runs = reading.runs if compare else sorted(reading.runs, key=lambda run: natural_key(run.name))
    steps, difference = reading.steps, reading.difference
    width = encoding.code_bytes(len(steps))
    runs_data = [dict(name=run.name, steps=run.steps, counts=run.counts, last=run.last,
                      lastViolations=run.last_violations, start=run.start, startViolations=run.start_violations,
                      kept=len(run.codes), codes=encoding.pack(run.codes, width)) for run in runs]
    conjunction = Conjunction.of(model)
    # The simulator's tables: per supervisor its alphabet and, per state, its [event, target]
    # pairs, so the page can fire any event from any vector, not only those the traces reached.
    alphabets = [sorted(sup.alphabet) for sup in model.supervisors]
    tables = [[[[e, t] for e, t, _ in transitions] for transitions in sup.states] for sup in model.supervisors]
    controllable = sum(1 << e for e, c in enumerate(model.controllable) if c)
    vector_list = steps.vectors.values()
    return dict(title=title, first=runs[0].first if runs else 1, window=window(len(runs)), robotSteps=ROBOT_STEPS,
                events=[[name, "c" if c else "u", int(p)]
                        for name, c, p in zip(model.events, model.controllable, model.public)],
                supervisors=[len(sup.states) for sup in model.supervisors],
                vectors=vector_list,
                enabled=[list(events_of(conjunction.enabled(tuple(v)) & controllable)) for v in vector_list],
                fired=steps.fired.values(), table=[list(row) for row in zip(steps.vector, steps.events, steps.added)],
                codeBytes=width, runs=runs_data, compare=compare,
                source=model.source, alphabets=alphabets, tables=tables,
                difference=difference.first if difference else None,
                differences=difference.steps if difference else 0,
                differenceShown=difference.shown if difference else None)


def asset(name: str) -> str:
    """The page's script or style from the package data (tests check neither holds ``</``)."""
    return TEMPLATES.joinpath("inspect", name).read_text(encoding="utf-8")


def _drawings(model: Model, title: str) -> str:
    figures = []
    for sup in range(len(model.supervisors)):
        svg = inline_svg(dot_to_svg(supervisor_dot(model, sup, "%s supervisor %d" % (title, sup)), model.source))
        figures.append('<figure class="sup" data-sup="%d"><figcaption>supervisor %d <span class="where"></span>'
                       '</figcaption>%s</figure>' % (sup, sup, svg))
    return "\n".join(figures)


def page_html(model: Model, title: str, reading: Reading, compare: bool) -> bytes:
    """The whole page, as UTF-8 bytes."""
    head = ('<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
            '<meta http-equiv="Content-Security-Policy" content="%s">\n'
            '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
            '<title>%s: swarmvm inspect</title>\n<style>\n%s</style>\n</head>\n'
            % (_CSP, html(title), asset("inspect.css")))
    body = (BODY % dict(title=html(title), drawings=_drawings(model, title))
            + '<script id="data" type="application/json">%s</script>\n<script>\n%s</script>\n</body>\n</html>\n'
            % (script_json(page_data(model, title, reading, compare)), asset("inspect.js")))
    return (head + body).encode("utf-8")


# The page's fixed structure; inspect.js fills it in. Only ``title`` and ``drawings`` are
# substituted, both escaped (html(), and Graphviz' own XML escaping of the DOT's labels).
BODY = """<body>
<header>
<h1>%(title)s</h1>
<p id="summary"></p>
<ul class="legend">
<li><span class="key controllable">controllable</span> solid edge: the VM chooses it</li>
<li><span class="key uncontrollable">uncontrollable</span> dashed edge: an input (a check)</li>
<li><span class="key public">public</span> bold edge: sent to the neighbours</li>
<li><span class="key current">current state</span> of the robot shown (count: robots in that state)</li>
<li><span class="key other">second run</span> when two runs are compared</li>
</ul>
</header>
<nav id="controls">
<button id="begin" title="first step (Home)">&#x00AB;</button>
<button id="back" title="step back (Left)">&#x25C0;</button>
<button id="play" title="play / pause (Space)">play</button>
<button id="forward" title="step forward (Right)">&#x25B6;</button>
<button id="end" title="last step (End)">&#x00BB;</button>
<input id="slider" type="range" min="0" max="0" value="0" aria-label="step">
<span id="stepLabel"></span>
<label>speed <select id="speed"><option value="1">1</option><option value="4" selected>4</option>
<option value="16">16</option><option value="64">64</option></select> steps/s</label>
<label>event <select id="event"><option value="-1">(any)</option></select></label>
<label><input id="filter" type="checkbox"> only its steps in the log</label>
<button id="nextEvent" title="next occurrence of the event (e)">next event</button>
<button id="nextViolation" title="next violation (v)">next violation</button>
<button id="difference" title="first difference" hidden>first difference</button>
<button id="prevDifference" title="previous difference (D)" hidden>previous difference</button>
<button id="nextDifference" title="next difference (d)" hidden>next difference</button>
<label>go to step <input id="goto" type="number" min="0" size="7"></label>
<label>find <input id="find" type="search" size="12" placeholder="EV_x or 2=q3"
title="an event (EV_x): the steps where it fires; a state (supervisor=qN): the steps where it is entered"></label>
<button id="findNext" title="next match (Enter in the box; Shift+Enter: previous)">find next</button>
<span id="status" role="status"></span>
</nav>
<details id="keys"><summary>Keyboard</summary>
<table>
<tr><td><kbd>&#x2190;</kbd> <kbd>&#x2192;</kbd></td><td>step back / forward (with <kbd>Shift</kbd>: 10 steps)</td></tr>
<tr><td><kbd>Home</kbd> <kbd>End</kbd></td><td>first / last step</td></tr>
<tr><td><kbd>Space</kbd></td><td>play / pause</td></tr>
<tr><td><kbd>+</kbd> <kbd>-</kbd></td><td>faster / slower</td></tr>
<tr><td><kbd>e</kbd> <kbd>E</kbd></td><td>next / previous step where the chosen event fired (in the robot shown while it has one)</td></tr>
<tr><td><kbd>v</kbd> <kbd>V</kbd></td><td>next / previous violation (likewise)</td></tr>
<tr><td><kbd>d</kbd> <kbd>D</kbd></td><td>next / previous difference of the two runs compared, among the steps kept</td></tr>
<tr><td><kbd>z</kbd> <kbd>Z</kbd></td><td>zoom the timeline in / out around the step shown (or Ctrl+wheel over it; drag to pan)</td></tr>
<tr><td><kbd>m</kbd></td><td>mark the step shown, or unmark it (the marks are kept in the page's address)</td></tr>
<tr><td><kbd>.</kbd> <kbd>,</kbd></td><td>next / previous mark</td></tr>
<tr><td><kbd>g</kbd> <kbd>/</kbd></td><td>the go-to-step box / the find box (<kbd>Esc</kbd>: back to these keys)</td></tr>
<tr><td><kbd>n</kbd></td><td>simulator: end the step with the VM's choice</td></tr>
<tr><td><kbd>u</kbd></td><td>simulator: undo the last event fired</td></tr>
<tr><td><kbd>&#x2191;</kbd> <kbd>&#x2193;</kbd></td><td>previous / next robot</td></tr>
</table>
</details>
<section id="lanes"><h2>Robots</h2>
<div id="zoom"><button id="zoomIn" title="zoom in (z)">zoom in</button><button id="zoomOut" title="zoom out (Z)">zoom out</button>
<button id="zoomAll" title="the whole window of steps">all steps</button> <span id="zoomLabel"></span>
<button id="mark" title="mark the step shown, or unmark it (m)">mark</button>
<button id="prevMark" title="previous mark (,)">previous mark</button><button id="nextMark" title="next mark (.)">next mark</button>
<span id="markList"></span></div>
<div id="laneBox"><div id="laneNames"></div><canvas id="timeline" width="1000" height="40"></canvas></div>
<div id="chartBox"><label>robots per state of <select id="chartSup"></select></label>
<canvas id="chart" width="1000" height="80"></canvas>
<span id="chartNow"></span><div id="chartLegend"></div></div>
</section>
<div id="here">
<section id="now"><h2>At this step</h2><div id="panels"></div></section>
<section id="sim"><h2>Simulator</h2>
<p id="simFrom"></p>
<div id="simEvents"></div>
<div id="simControls">
<button id="simStep" title="end the step: the VM chooses its event (n)">end step (VM's choice)</button>
<button id="simUndo" title="undo the last event fired (u)">undo</button>
<button id="simReset" title="back to where the simulation started">reset</button>
<label>seed <input id="simSeed" type="number" min="0" max="4294967295" value="1"></label>
<label>policy <select id="simPolicy"><option value="uniform">uniform</option><option value="first">first</option></select></label>
<button id="simSave" title="download the path as an event script">save script</button>
</div>
<p id="simStatus" role="status"></p>
<table id="simLog"></table>
<details id="simScriptBox"><summary>event script</summary><pre id="simScript"></pre></details>
</section>
</div>
<section id="drawings"><h2>Supervisors</h2>
<label id="depthBox">show <select id="depth"><option value="-1" selected>every state</option>
<option value="1">1 transition</option><option value="2">2 transitions</option><option value="3">3 transitions</option>
</select> around the current state (for large supervisors)</label>
%(drawings)s
</section>
<section id="log"><h2>Trace</h2><table id="logTable"></table></section>
<section id="runs"><h2>Whole runs</h2><table id="runTable"></table></section>
"""


@dataclass(frozen=True)
class Inspection:
    """What ``swarmvm inspect`` wrote: the page's path, and the robot-steps of the traces it
    keeps in full and in all (fewer kept when over :data:`ROBOT_STEPS`)."""
    path: str
    kept: int
    total: int


def write_page(model: Model, title: str, traces: Sequence[str], output: str, compare: bool,
               first_step: int) -> Inspection:
    """Read every trace (InputError at the first bad line, before anything is written), then
    write the page to ``output`` atomically."""
    reading = read_runs(traces, model, first_step, window(len(traces)), compare and len(traces) == 2)
    target = Path(output).absolute()
    written = write_outputs(target.parent, {target.name: (page_html(model, title, reading, compare), False)})
    runs = reading.runs
    return Inspection(written[0], sum(len(r.codes) for r in runs), sum(max(0, r.steps - r.first + 1) for r in runs))
