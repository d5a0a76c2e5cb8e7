# swarmvm: `make demo` runs the main job on the bundled example, `make test` the test suite.
# Both run `make setup` first (scripts/setup.sh: Debian packages, then the project's own venv
# .venv/ with `pip install -e .[test]`; idempotent). Every rule runs Python and the CLI from it.
# Per-area rules (firmware images, emulator runs, benchmarks) live in mk/*.mk.

VENV ?= .venv
PYTHON ?= $(VENV)/bin/python
SWARMVM ?= $(VENV)/bin/swarmvm
BUILD ?= build
# The suite on every core (pytest-xdist; tests/conftest.py groups what shares fixtures);
# TEST_WORKERS=0 runs it in one process.
TEST_WORKERS ?= auto
PYTEST_PARALLEL = $(if $(filter 0,$(TEST_WORKERS)),,-n $(TEST_WORKERS) --dist loadgroup)
EXAMPLE ?= examples/energy_worker/supervisor.yaml
# Kilobot images (mk/kilobot.mk): STREAM=1 builds the streaming variant, apart.
KILOBOT_OUT := $(BUILD)/kilobot$(if $(filter 1,$(STREAM)),-stream)

.PHONY: setup test typecheck test-quick demo bench gen firmware footprint golden wheel-check clean

setup:
	@VENV=$(VENV) scripts/setup.sh

# `make prove` first (mk/prove.mk: Eva over the C runtime, its alarms against tests/proof/alarms.txt;
# its timings: docs/proof.md).
test: setup typecheck
	$(MAKE) --no-print-directory prove
	$(PYTHON) -m pytest tests $(PYTEST_PARALLEL)

typecheck: setup
	$(PYTHON) -m mypy
	$(PYTHON) -m ruff check generator runtime_py studies tests benchmarks firmware scripts

# The fast part of the suite (no emulator, nothing slow): about a minute and a half.
test-quick: setup
	$(PYTHON) -m pytest tests -m "not emulator and not slow" $(PYTEST_PARALLEL)

# Rewrite the golden copies (tests/golden/) after an intended change: every target's generated code
# for the example and the feature models of tests/golden/golden.py, and gen's refusal messages.
golden: setup
	$(PYTHON) tests/golden/golden.py

# Build the wheel, install it into a fresh venv outside the checkout, compare every verb's output
# with the editable install's and run the CLI tests against it (scripts/check_wheel.sh).
wheel-check: setup $(BUILD)/kilobot/energy_worker.elf $(BUILD)/capbot/energy_worker.elf
	scripts/check_wheel.sh $(VENV)

# Generate every target for the bundled example into build/gen/<target>/.
gen:
	@for t in $$($(PYTHON) -c "from swarmvm.targets import TARGETS; print(' '.join(sorted(TARGETS)))"); do \
	  $(SWARMVM) gen $(EXAMPLE) --target $$t -o $(BUILD)/gen/$$t --name energy_worker >/dev/null || exit 1; \
	  echo "generated $(BUILD)/gen/$$t"; done

demo: setup
	$(MAKE) -s --no-print-directory gen firmware emulate argos-demo footprint

# The benchmarks of mk/*.mk run first (prerequisites of bench), then these, then issue 13's
# scorecard, which reads what they and `make footprint` wrote.
bench: setup footprint
	$(PYTHON) benchmarks/python_vm.py
	$(PYTHON) benchmarks/python_vs_baseline.py --json $(BUILD)/bench/python_vs_baseline.json
	$(PYTHON) benchmarks/sct_exact.py --json $(BUILD)/bench/sct_exact.json
	$(PYTHON) benchmarks/issue13.py --json $(BUILD)/bench/issue13.json
	$(PYTHON) benchmarks/inspect_page.py --json $(BUILD)/bench/inspect_page.json

clean:
	rm -rf $(BUILD)

# The per-area rules of mk/*.mk run the venv's Python and CLI: each sets up first, as test and
# demo do, so that it works on a fresh clone (tests/cli/test_make_targets.py). A rule whose own
# line lists files to build names setup there, first (emulate, footprint): make builds those first.
SET_UP_FIRST := gen firmware argos argos-demo kilolib kilobot-board kilobot-firmware capbot-firmware \
	kilobot-swap-demo models learning-size uav-runs uav-grid energy-grid \
	bench-c-host bench-m4 bench-cpp bench-avr bench-learning bench-drone bench-energy
$(SET_UP_FIRST): setup

-include mk/*.mk
