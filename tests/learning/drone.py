"""The drone-delivery learning setting of the OpenSwarm study for the learning tests: the
study's features (swarmvm.studies.drone_delivery.features), a labelled task stream and a grid."""

import random

from swarmvm.studies.drone_delivery.features import MEAN, SCALE, SEED_LABELS, SEED_POINTS

__all__ = ["MEAN", "SCALE", "SEED_LABELS", "SEED_POINTS", "delivery_stream", "grid"]


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
