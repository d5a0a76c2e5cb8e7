# Studies (studies/, docs/studies/): the drone-delivery benchmark, and the runs behind the
# reproduction page (reduced grid; `make uav-grid` is the seed's full grid).
#   make bench         also reports seconds per simulated week of the drone-delivery study
#   make uav-runs      the runs and figures of docs/studies/drone-delivery.md
#   make uav-grid      the full grid: 3 rules + 6 thresholds x tau 5..30 x 20 runs x 8 weeks
#   make bench         also reports seconds per energy-replenishment trial in real ARGoS against
#                      the same robots with an empty controller
#   make energy-grid   the energy study's full grids (Figures 9-12, 50 trials per configuration,
#                      3,000 ARGoS trials) and their figures; ENERGY_RUNS=10 for a reduced grid

.PHONY: bench-drone bench-energy uav-runs uav-grid energy-grid

UAV_OUT ?= $(BUILD)/uav-sweep
UAV_WORKERS ?= 2

bench: bench-drone bench-energy

bench-drone:
	$(PYTHON) benchmarks/drone_delivery.py

bench-energy:
	$(PYTHON) benchmarks/energy_study.py --json $(BUILD)/bench/energy_study.json

uav-runs:
	sh scripts/uav_runs.sh $(SWARMVM) $(UAV_OUT) $(UAV_WORKERS)

uav-grid:
	$(SWARMVM) sweep uav -o $(BUILD)/uav-grid --workers $(UAV_WORKERS)
	$(SWARMVM) plot uav $(BUILD)/uav-grid -o $(BUILD)/uav-grid/img

ENERGY_OUT ?= $(BUILD)/energy-grid
ENERGY_RUNS ?= 50
ENERGY_WORKERS ?= 2

energy-grid:
	$(SWARMVM) sweep energy -o $(ENERGY_OUT) --runs $(ENERGY_RUNS) --workers $(ENERGY_WORKERS)
	$(SWARMVM) plot energy $(ENERGY_OUT) -o $(ENERGY_OUT)/img
