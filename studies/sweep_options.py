"""The options every sweep shares, checked before any trial runs: ``--runs``, ``--workers`` (local
processes) and the seeds ``--first-seed`` .. ``--first-seed + --runs - 1``, each of which must
be a seed the study's ``sim`` verb takes, so that a sweep neither stops part-way on a seed its
trials refuse nor runs one that ``sim`` would refuse."""

from __future__ import annotations

import click

# Runs per configuration a sweep takes: 20 times the seed's 50, and few enough that a grid's
# trial specifications, all listed before the first trial runs, stay small (docs/limits.md).
MAX_RUNS = 1_000
RUNS = click.IntRange(1, MAX_RUNS)
# Local processes a sweep starts at once (never more than it has trials to run): each runs one
# trial, so more than the machine's cores gain nothing, and an unbounded count would fork until
# the machine runs out of processes.
MAX_PROCESSES = 1024
PROCESSES = click.IntRange(1, MAX_PROCESSES)


def sweep_seeds(first: int, runs: int, largest: int) -> range:
    """first .. first + runs - 1; a usage error on ``--first-seed`` when the last passes ``largest``."""
    last = first + runs - 1
    if last > largest:
        raise click.BadOptionUsage("--first-seed", "the seeds %d..%d (--runs %d) pass %d, the largest seed: "
                                                   "lower --first-seed or --runs" % (first, last, runs, largest))
    return range(first, last + 1)
