"""The inspector's page (docs/inspect.md) of traces written by a runtime: what each of its steps
holds, for the conformance tests of the C VM in simavr and of the generated controller in ARGoS,
which check it against the traces themselves."""

import json
import re
from pathlib import Path

from swarmvm import api
from swarmvm.inspector.encoding import decode

DATA = re.compile(r'<script id="data" type="application/json">(.*?)</script>', re.S)


def inspected_states(supervisor, traces: dict, folder: Path) -> dict:
    """{run: the states of each step} as the page of ``traces`` ({run: canonical trace lines},
    one lane each) holds them."""
    files = []
    for run, lines in sorted(traces.items()):
        files.append(folder / ("%s.trace" % run))
        files[-1].write_text("".join(line + "\n" for line in lines))
    page = api.inspect(str(supervisor), [str(f) for f in files], str(folder / "page.html"))
    data = json.loads(DATA.search(Path(page.path).read_text()).group(1))
    lanes = {Path(lane["name"]).name.removesuffix(".trace"): lane for lane in data["runs"]}   # in natural order
    assert sorted(lanes) == sorted(traces)
    return {run: [states for states, _fired, _violations in decode(data, lanes[run])[1:]] for run in traces}


def states_of(traces: dict) -> dict:
    """{run: the states of each step} read from the canonical trace lines themselves."""
    return {run: [[int(s) for s in line.split()[2].split(",")] for line in lines] for run, lines in traces.items()}
