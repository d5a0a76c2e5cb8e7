# Real ARGoS (scripts/argos.sh finds an installed ARGoS or builds it once from ARGOS_SRC into
# ~/.cache/swarmvm/) and the argos target run in it.
#   make argos        find or build ARGoS; prints its install prefix
#   make argos-demo   generate the bundled example for the argos target into $(ARGOS_DEMO), build
#                     the controller with its own CMakeLists.txt against that ARGoS, run the
#                     generated .argos as it is (6 e-pucks in a walled arena, 300 control steps,
#                     headless) and print each robot's summary line
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
	@prefix=$$(scripts/argos.sh) && \
	  mkdir -p $(ARGOS_DEMO) && find $(ARGOS_DEMO) -maxdepth 1 -type f -delete && \
	  $(SWARMVM) gen $(EXAMPLE) --target argos -o $(ARGOS_DEMO) --name energy_worker >/dev/null && \
	  cmake -S $(ARGOS_DEMO) -B $(ARGOS_DEMO)/build -DCMAKE_BUILD_TYPE=Release -DARGOS_PREFIX=$$prefix \
	    >$(ARGOS_DEMO)/cmake.log 2>&1 && cmake --build $(ARGOS_DEMO)/build >>$(ARGOS_DEMO)/cmake.log 2>&1 || \
	  { cat $(ARGOS_DEMO)/cmake.log; exit 1; }; \
	  echo "argos-demo: $(ARGOS_DEMO)/energy_worker.argos in ARGoS at $$prefix (log: $(ARGOS_DEMO)/argos.log)"; \
	  cd $(ARGOS_DEMO) && $(CURDIR)/scripts/argos.sh run -n -c energy_worker.argos -l argos.log -e argos.err || \
	  { cat argos.err; exit 1; }; grep '^summary ' argos.log
