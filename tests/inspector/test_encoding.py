"""The compact encoding of a page's runs (swarmvm.inspector.encoding, docs/inspect.md "Size"):
random runs written as traces, read back block by block (swarmvm.inspector.trace) and packed,
decode to the runs they were, step by step, whatever the blocks' size, the blank lines, the line
endings or the codes' width; two runs compared chunk by chunk differ where a line-by-line
comparison says they do."""

import base64
from array import array
from unittest import mock

import pytest
from hypothesis import example, given, strategies as st

from inspect_cases import NETWORK_WORKER
from swarmvm import api
from swarmvm.boundary.errors import InputError
from swarmvm.inspector import encoding, page, trace
from swarmvm.inspector.encoding import decode, pack, unpack

MODEL = api.compile_model([str(NETWORK_WORKER)]).model
SIZES = [len(sup.states) for sup in MODEL.supervisors]

# One step: the events fired (by index), the states after, the violation counter after.
steps = st.tuples(st.lists(st.integers(0, len(MODEL.events) - 1), max_size=4),
                  st.tuples(*(st.integers(0, size - 1) for size in SIZES)).map(list),
                  st.integers(0, 40))
runs = st.lists(steps, max_size=60)


def trace_text(run, blank_after=(), ending="\n", last_newline=True) -> str:
    lines = [ending] if 0 in blank_after else []
    for step, (fired, states, violations) in enumerate(run, 1):
        names = ",".join("EV_" + MODEL.events[e] for e in fired) or "-"
        lines.append("%d %s %s %d" % (step, names, ",".join(map(str, states)), violations) + ending)
        if step in blank_after:
            lines.append(ending)
    text = "".join(lines)
    return text if last_newline or not text else text[:-len(ending)]


def written(tmp_path, texts) -> list[str]:
    paths = []
    for n, text in enumerate(texts):
        paths.append(str(tmp_path / ("robot%d.trace" % n)))
        (tmp_path / ("robot%d.trace" % n)).write_bytes(text.encode())
    return paths


def expected(run, first=1, window=None):
    """What decode must give: index 0, the states before step ``first``, then each step kept."""
    before = run[first - 2] if first > 1 else ([], [0] * len(SIZES), 0)
    kept = run[first - 1:] if window is None else run[first - 1:first - 1 + window]
    return [(before[1], [], before[2])] + [(states, fired, violations) for fired, states, violations in kept]


@given(st.lists(runs, min_size=1, max_size=4), st.integers(8, 200), st.sets(st.integers(0, 60), max_size=8),
       st.sampled_from(["\n", "\r\n"]), st.booleans(), st.booleans())
@example([[([1], [0] * len(SIZES), 0)] * 5], 8, {0, 1, 2, 4}, "\n", False, False)
def test_random_runs_decode_to_themselves(tmp_path_factory, all_runs, block, blank_after, ending, last_newline,
                                          wide):
    """Blocks of 8 to 200 bytes (a line cut anywhere), codes of 2 or 4 bytes."""
    folder = tmp_path_factory.mktemp("runs")
    paths = written(folder, [trace_text(run, blank_after, ending, last_newline) for run in all_runs])
    with mock.patch.object(trace, "BLOCK", block), mock.patch.object(encoding, "SHORT", 1 if wide else 1 << 16):
        reading = trace.read_runs(paths, MODEL, 1, 10 ** 6)
        data = page.page_data(MODEL, "t", reading, False)
    assert data["codeBytes"] == (4 if wide and len(data["table"]) > 1 else 2)
    by_name = {run["name"]: run for run in data["runs"]}
    for path, run in zip(paths, all_runs):
        lane = by_name[path.rsplit("/", 1)[1]]
        assert decode(data, lane) == expected(run)
        assert lane["steps"] == len(run) and lane["kept"] == len(run)
        assert lane["counts"] == [sum(fired.count(e) for fired, _, _ in run) for e in range(len(MODEL.events))]
        assert data["vectors"][lane["last"]] == (run[-1][1] if run else [0] * len(SIZES))
        assert lane["lastViolations"] == (run[-1][2] if run else 0)


@given(runs.filter(lambda run: len(run) >= 3), st.data())
def test_a_window_keeps_its_steps_and_the_state_before(tmp_path_factory, run, data):
    first = data.draw(st.integers(1, len(run)))
    window = data.draw(st.integers(1, len(run)))
    paths = written(tmp_path_factory.mktemp("window"), [trace_text(run)])
    with mock.patch.object(trace, "BLOCK", 64):
        reading = trace.read_runs(paths, MODEL, first, window)
    lane = page.page_data(MODEL, "t", reading, False)["runs"][0]
    assert decode(page.page_data(MODEL, "t", reading, False), lane) == expected(run, first, window)
    assert lane["steps"] == len(run) and lane["startViolations"] == (run[first - 2][2] if first > 1 else 0)


def line_differences(a, b):
    """The steps whose lines differ, one run's line against the other's (or none)."""
    lines_a, lines_b = trace_text(a).splitlines(), trace_text(b).splitlines()
    return [n for n in range(1, max(len(lines_a), len(lines_b)) + 1)
            if lines_a[n - 1:n] != lines_b[n - 1:n]]


@given(runs, st.data(), st.integers(1, 9))
def test_two_runs_compared_chunk_by_chunk_differ_where_their_lines_do(tmp_path_factory, a, data, chunk):
    """The second run is the first with some steps changed (an event, a state or a counter: a
    counter changed shifts no later line, a counter put back makes codes differ where lines
    do not) and cut or lengthened; compared a chunk of 1 to 9 codes at a time."""
    b = [list(step) for step in a]
    for n in data.draw(st.sets(st.integers(0, max(0, len(b) - 1)), max_size=4)) if b else ():
        b[n] = list(data.draw(steps))
    b = b[:data.draw(st.integers(0, len(b)))] + data.draw(st.lists(steps, max_size=3))
    b = [tuple(step) for step in b]
    paths = written(tmp_path_factory.mktemp("compare"), [trace_text(a), trace_text(b)])
    differ = line_differences(a, b)
    first = data.draw(st.integers(1, max(1, len(a), len(b))))
    with mock.patch.object(trace, "CHUNK", chunk), mock.patch.object(trace, "BLOCK", 50):
        if any(0 < len(run) < first for run in (a, b)):
            with pytest.raises(InputError, match="nothing from step %d on" % first):
                trace.read_runs(paths, MODEL, first, 5, compare=True)
            return
        difference = trace.read_runs(paths, MODEL, first, 5, compare=True).difference
    assert difference == trace.Difference(differ[0] if differ else None, len(differ),
                                          next((n for n in differ if first <= n < first + 5), None))


@pytest.mark.parametrize("chunk", [1, 2, 100])
def test_a_counter_ahead_makes_every_later_line_differ(tmp_path, chunk):
    """The same events and states, the second run's counter one ahead from step 2 on: steps 2 to
    4 differ though from step 3 on their codes (violations added) are the same."""
    same = ([1], [0] * len(SIZES))
    a = [same + (0,)] * 4
    b = [same + (0,)] + [same + (1,)] * 3
    paths = written(tmp_path, [trace_text(a), trace_text(b)])
    with mock.patch.object(trace, "CHUNK", chunk):
        assert trace.read_runs(paths, MODEL, 1, 10, compare=True).difference == trace.Difference(2, 3, 2)
        assert trace.read_runs(paths, MODEL, 4, 10, compare=True).difference == trace.Difference(2, 3, 4)


@given(st.lists(st.integers(0, (1 << 32) - 1)), st.sampled_from([2, 4]))
def test_codes_pack_to_little_endian_base64_and_back(codes, width):
    codes = [c % (1 << 16) for c in codes] if width == 2 else codes
    text = pack(array("I", codes), width)
    assert unpack(text, width) == codes
    assert len(text) == 4 * -(-len(codes) * width // 3)
    raw = base64.b64decode(text)
    assert [int.from_bytes(raw[n:n + width], "little") for n in range(0, len(raw), width)] == codes
