"""The bidding features of the study and their learning setting (design/STUDIES.md), shared by
the simulator and the learning tests: (distance m, parcel mass kg, SoC %), standardised with the
mean and deviation of their ranges, and the two assumed points of the initial fit."""

MEAN = (3500.0, 2.75, 50.0)
SCALE = (1443.38, 1.299, 28.87)
SEED_POINTS = [(1000.0, 0.5, 100.0), (6000.0, 5.0, 0.0)]   # full, easiest: yes; empty, hardest: no
SEED_LABELS = [1, 0]
