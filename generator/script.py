"""Event scripts: the target-independent input of the conformance contract (docs/conformance.md).

A script says, for each step, which uncontrollable events' checks return true. As text: one
line per step listing ``EV_`` names separated by spaces, or ``-`` for none; ``#`` starts a
comment line."""

import random

from .errors import InputError


def parse_script(path, text, names, controllable):
    """Text -> list of sets of event indices. ``names`` are the image's bare event names."""
    index = {"EV_" + n: i for i, n in enumerate(names)}
    rows = []
    for number, line in enumerate(text.splitlines(), 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        row = set()
        if line != "-":
            for token in line.split():
                if token not in index:
                    raise InputError(path, "line %d" % number, "unknown event", "event %s" % token)
                if controllable >> index[token] & 1:
                    raise InputError(path, "line %d" % number, "controllable events are chosen by the VM, "
                                     "not scripted", "event %s" % token)
                row.add(index[token])
        rows.append(row)
    return rows


def script_lines(rows, names):
    """Rows of event indices -> the script's lines, without newlines (events in index order),
    one at a time: a script of millions of steps is written in constant memory."""
    yield "# swarmvm event script: one step per line, the uncontrollable events that occur"
    for row in rows:
        yield " ".join("EV_" + names[e] for e in sorted(row)) or "-"


def format_script(rows, names):
    """Rows of event indices -> script text."""
    return "".join(line + "\n" for line in script_lines(rows, names))


def random_rows(tables, steps, seed, density=0.25):
    """A reproducible random script over the model's uncontrollable events, row by row."""
    rng = random.Random(seed)
    uncontrollable = [e for e in range(tables.num_events) if not tables.controllable >> e & 1]
    for _ in range(steps):
        yield {e for e in uncontrollable if rng.random() < density}


def random_script(tables, steps, seed, density=0.25):
    """The rows of :func:`random_rows` as a list."""
    return list(random_rows(tables, steps, seed, density))
