"""Who wins an auction (design/STUDIES.md): every bid is normalised by the largest, the winner
minimises |b / max - A| with the anchor A = 0 for the least confident rule and 1 for the others
(most confident; random, whose bids are U[0, 1) draws; threshold, whose bids are SoCs), and a
tie goes to the highest drone id."""

from __future__ import annotations

import numpy as np

ANCHOR = {"least-confident": 0.0, "most-confident": 1.0, "random": 1.0, "threshold": 1.0}


def winners(values: np.ndarray, bidding: np.ndarray, rule: str) -> np.ndarray:
    """Per column (one auction each), the row (drone id) of the winner, -1 without a bid.

    ``values`` and ``bidding`` are (drones x auctions); rows are drone ids in ascending order."""
    values = np.where(bidding, values, -np.inf)
    top = values.max(axis=0)
    scale = np.where(top > 0.0, top, 1.0)
    key = np.where(bidding, np.abs(values / scale - ANCHOR[rule]), np.inf)
    last = key.shape[0] - 1 - np.argmin(key[::-1], axis=0)   # ties: the highest id
    return np.where(bidding.any(axis=0), last, -1)


def winner(ids, values, rule: str) -> int:
    """The winning drone id among ``ids`` (ascending) bidding ``values``; -1 if nobody bid."""
    if not len(ids):
        return -1
    column = np.asarray(values, dtype=float).reshape(-1, 1)
    row = winners(column, np.ones_like(column, dtype=bool), rule)[0]
    return int(ids[row])


def lowest(ids, values) -> int:
    """Reservations: the lowest value wins, a tie goes to the highest id; -1 if none."""
    if not len(ids):
        return -1
    values = np.asarray(values, dtype=float)
    return int(ids[len(values) - 1 - int(np.argmin(values[::-1]))])
