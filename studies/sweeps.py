"""The sweep runner every study shares: a list of trial specifications run on local processes or
on a Dask cluster, resumable, written as tidy Parquet tables.

A study gives its specifications (any picklable value, each a pure function of its seed and
parameters, so results do not depend on where or in which order trials run), a key per trial
(a readable, unique file name), the module-level function that runs one trial and returns its
rows for every table, and its table names. Each finished trial is written as one Parquet file
per table under ``OUT/<table>/<key>.parquet``, the ``trials`` table last: its presence marks the
trial done, and a rerun skips done trials."""

from __future__ import annotations

import contextlib
import functools
import hashlib
import io
import json
import multiprocessing
import shlex
import signal
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple

from ..boundary.errors import TABLE_MAX_BYTES, read_input
from ..boundary.output import write_outputs

if TYPE_CHECKING:
    import pandas

Tables = Dict[str, list]


def digest(values: dict) -> str:
    """A short digest of a trial's parameters: keys stay unique however the label reads."""
    return hashlib.sha1(json.dumps(values, sort_keys=True).encode()).hexdigest()[:10]


def write_trial(out: Path, key: str, tables: Tables, names: Sequence[str]) -> None:
    """One Parquet file per table, drawn in memory and written through the output layer
    (swarmvm.boundary.output): the other tables as one transaction, then ``trials`` (which
    marks the trial done, :func:`done_keys`) as another, so that a trial interrupted between
    them is run again. The folders are made first (several workers may make them at once)."""
    import pandas as pd
    files: Dict[str, Tuple[bytes, bool]] = {}
    for table in names:
        (out / table).mkdir(parents=True, exist_ok=True)
        data = io.BytesIO()
        pd.DataFrame(tables[table]).to_parquet(data, index=False)
        files["%s/%s.parquet" % (table, key)] = (data.getvalue(), False)
    last = "trials/%s.parquet" % key
    write_outputs(out, {rel: value for rel, value in files.items() if rel != last})
    if last in files:
        write_outputs(out, {last: files[last]})


def read_table(path: Path) -> "pandas.DataFrame":
    """One trial's Parquet table, read through the input layer (a regular file, TABLE_MAX_BYTES
    at most: swarmvm.boundary.errors.read_input)."""
    import pandas as pd
    return pd.read_parquet(io.BytesIO(read_input(str(path), limit=TABLE_MAX_BYTES)))


def done_keys(out: Path) -> set:
    folder = out / "trials"
    return {p.stem for p in folder.glob("*.parquet")} if folder.exists() else set()


def run(specs: Sequence[Any], key: Callable[[Any], str], run_trial: Callable[[Any], Tables], out, names: Sequence[str],
        workers: int = 1, scheduler: Optional[Any] = None, progress: bool = True) -> int:
    """Runs the trials of ``specs`` not yet in ``out``; returns how many ran. ``scheduler``: a
    Dask scheduler address (``tcp://host:8786``) or a ``distributed.Client``; otherwise
    ``workers`` local processes (1: in this process). Duplicate specifications run once."""
    from tqdm import tqdm
    out = Path(out)
    done = done_keys(out)
    todo = list({key(s): s for s in specs if key(s) not in done}.items())
    with _cluster(scheduler if todo else None) as client:
        bar = tqdm(total=len(todo), disable=not progress, unit="trial")
        for name, tables in _results(todo, run_trial, workers, client):
            write_trial(out, name, tables, names)
            bar.update(1)
        bar.close()
    return len(todo)


class SchedulerError(Exception):
    """The Dask scheduler given cannot be reached (the message names --scheduler and why)."""


@contextlib.contextmanager
def _cluster(scheduler) -> Iterator[Any]:
    """A client of the scheduler (an address, connected here before any trial is counted, and
    closed after; or a client, used as it is), or None to run locally."""
    if scheduler is None:
        yield None
        return
    from distributed import Client
    if isinstance(scheduler, Client):
        yield scheduler
        return
    try:
        client = Client(scheduler)
    except (OSError, ValueError, TypeError) as exc:      # unreachable, or not an address
        raise SchedulerError("--scheduler: %s" % exc) from None
    try:
        yield client
    finally:
        client.close()


def _results(todo: List[Tuple[str, Any]], run_trial, workers: int, client) -> Iterator[Tuple[str, Tables]]:
    """(key, tables) as trials finish."""
    if not todo:                        # a sweep resumed when all its trials are done
        return
    if client is not None:
        from distributed import as_completed as dask_completed
        futures = client.map(run_trial, [s for _, s in todo], key=[k for k, _ in todo])
        for future in dask_completed(futures):
            yield future.key, future.result()
    elif workers <= 1:
        for name, spec in todo:
            yield name, run_trial(spec)
    else:
        # Leaving the pool, normally or by an exception (SIGTERM included, swarmvm.boundary.termination),
        # terminates its processes: a trial still running then stops, and its ARGoS with it,
        # instead of running on orphaned. The workers take SIGTERM's default action (they end
        # at once) rather than the verb's handler they are forked with.
        with multiprocessing.Pool(min(workers, len(todo)), initializer=_default_sigterm) as pool:
            yield from pool.imap_unordered(functools.partial(_keyed, run_trial), todo)


def _default_sigterm() -> None:
    """SIGTERM's default action again, in a pool's worker: it is forked with the verb's handler
    (swarmvm.boundary.termination), which would unwind the verb's code in it, and the pool's
    terminate() expects its workers to end at once."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _keyed(run_trial: Callable[[Any], Tables], item: Tuple[str, Any]) -> Tuple[str, Tables]:
    """(key, tables) of one trial, in a pool's process."""
    name, spec = item
    return name, run_trial(spec)


def check_trials(out, column: str, sweep: str) -> None:
    """A ValueError unless ``out`` holds finished trials of the study whose trials table has
    ``column`` (``sweep``: the command that writes them), so that a plot of an empty folder, or
    of the other study's, is one line rather than a traceback or an empty figure."""
    files = sorted((Path(out) / "trials").glob("*.parquet"))
    if not files:
        raise ValueError("%s: no finished trials in this folder (%s -o %s writes them)" % (out, sweep, shlex.quote(str(out))))
    if column not in read_table(files[0]).columns:
        raise ValueError("%s: these are not the trials of %s" % (out, sweep))


def load(out, names: Sequence[str], index: Sequence[str] = ("key",)) -> Dict[str, "pandas.DataFrame"]:
    """Every table of a sweep, sorted by the ``index`` columns it has (trial key first)."""
    import pandas as pd
    out = Path(out)
    frames = {}
    for table in names:
        files = sorted((out / table).glob("*.parquet"))
        frame = pd.concat([read_table(f) for f in files], ignore_index=True) if files else pd.DataFrame()
        columns = [c for c in index if c in frame.columns]
        frames[table] = frame.sort_values(columns).reset_index(drop=True) if columns else frame
    return frames
