# Studies (studies/, docs/studies/): the drone-delivery benchmark, and the runs behind the
# reproduction page (reduced grid; `make uav-grid` is the seed's full grid).
#   make bench         also reports seconds per simulated week of the drone-delivery study
#   make uav-runs      the runs and figures of docs/studies/drone-delivery.md
#   make uav-grid      the full grid: 3 rules + 6 thresholds x tau 5..30 x 20 runs x 8 weeks

.PHONY: bench-drone uav-runs uav-grid

UAV_OUT ?= $(BUILD)/uav-sweep
UAV_WORKERS ?= 2

bench: bench-drone

bench-drone:
	$(PYTHON) benchmarks/drone_delivery.py

uav-runs:
	sh scripts/uav_runs.sh $(SWARMVM) $(UAV_OUT) $(UAV_WORKERS)

uav-grid:
	$(SWARMVM) sweep uav -o $(BUILD)/uav-grid --workers $(UAV_WORKERS)
	$(SWARMVM) plot uav $(BUILD)/uav-grid -o $(BUILD)/uav-grid/img
