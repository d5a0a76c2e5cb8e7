# swarmvm: `make demo` runs the main job on the bundled example, `make test` the test suite.
# Both run `make setup` first (Debian packages and `pip install -e .[test]`, idempotent).
# Per-area rules (firmware images, emulator runs, benchmarks) live in mk/*.mk.

PYTHON ?= python3
SWARMVM ?= swarmvm
BUILD ?= build
EXAMPLE ?= examples/energy_worker/supervisor.yaml
# Kilobot images (mk/kilobot.mk): STREAM=1 builds the streaming variant, apart.
KILOBOT_OUT := $(BUILD)/kilobot$(if $(filter 1,$(STREAM)),-stream)

.PHONY: setup test demo bench gen firmware footprint clean

setup:
	@scripts/setup.sh

test: setup
	$(PYTHON) -m pytest tests

# Generate every target for the bundled example into build/gen/<target>/.
gen:
	@for t in $$($(PYTHON) -c "from swarmvm.targets import TARGETS; print(' '.join(sorted(TARGETS)))"); do \
	  $(SWARMVM) gen $(EXAMPLE) --target $$t -o $(BUILD)/gen/$$t --name energy_worker >/dev/null || exit 1; \
	  echo "generated $(BUILD)/gen/$$t"; done

demo: setup
	$(MAKE) -s --no-print-directory gen firmware emulate footprint

bench: setup
	$(PYTHON) benchmarks/python_vm.py

clean:
	rm -rf $(BUILD)

-include mk/*.mk
