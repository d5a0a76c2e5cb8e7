# Real ARGoS (scripts/argos.sh finds an installed ARGoS or builds it once from ARGOS_SRC into
# ~/.cache/swarmvm/) and the argos target run in it.
#   make argos        find or build ARGoS; prints its install prefix
#   make argos-demo   generate the bundled example for the argos target into $(ARGOS_DEMO), build
#                     the controller with its own CMakeLists.txt against that ARGoS, run the
#                     generated .argos as it is (6 e-pucks in a walled arena, 300 control steps,
#                     headless), then with an event script in place of the sensors, printing each
#                     robot's summary line and comparing its trace with swarmvm trace
#                     (firmware/argos_demo.py)
# `make test` first runs the find/build step, so the ARGoS tests find it; with no ARGoS and no
# source archive it goes on (the tests then skip, saying how to get ARGoS) unless CI=true.

ARGOS_DEMO ?= $(BUILD)/argos-demo

.PHONY: argos argos-demo argos-for-test

argos:
	@echo "ARGoS: $$(scripts/argos.sh)"

test: argos-for-test

argos-for-test:
	@scripts/argos.sh >/dev/null || { status=$$?; [ $$status -eq 3 ] && [ "$${CI:-}" != true ]; }

argos-demo:
	@$(PYTHON) firmware/argos_demo.py --example $(EXAMPLE) --name energy_worker --out $(ARGOS_DEMO)
