"""The drone-delivery learning setting of the OpenSwarm study (design/STUDIES.md), shared by the
learning tests: feature statistics, the two assumed training points and a labelled task stream."""

import random

MEAN = (3500.0, 2.75, 50.0)
SCALE = (1443.38, 1.299, 28.87)
SEED_POINTS = [(1000.0, 0.5, 100.0), (6000.0, 5.0, 0.0)]
SEED_LABELS = [1, 0]


def delivery_stream(count, seed):
    """Random tasks (distance m, mass kg, take-off SoC %) labelled by a noisy energy rule:
    delivered iff the SoC covers a need growing with distance and mass."""
    rng = random.Random(seed)
    for _ in range(count):
        distance, mass, soc = rng.uniform(1000, 6000), rng.uniform(0.5, 5), rng.uniform(0, 100)
        need = 100.0 * (distance / 6000.0) * (0.5 + mass / 10.0)
        yield (distance, mass, soc), int(soc + rng.gauss(0, 8) >= need)


def grid(size):
    """The probe's grid of raw features, in the probe's loop order (C computes them the same way)."""
    return [(1000.0 + 5000.0 * a / (size - 1), 0.5 + 4.5 * b / (size - 1), 100.0 * c / (size - 1))
            for a in range(size) for b in range(size) for c in range(size)]
