# The C VM on the host (runtime_c/, firmware/harness/ with platform_host.c).
#   make bench      also runs benchmarks/c_host.py: image loads and trace steps per second,
#                   current VM against the baseline (benchmarks/baseline.py), in one run

.PHONY: bench-c-host

bench: bench-c-host

bench-c-host:
	$(PYTHON) benchmarks/c_host.py --json $(BUILD)/bench/c_host.json
