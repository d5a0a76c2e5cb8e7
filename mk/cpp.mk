# C++ runtime (runtime_cpp/) and the argos / pipuck targets.
#   make bench        also runs the C++ steps-per-second benchmark (benchmarks/cpp_steps.py)
#   make argos-check  generates the ARGoS controller for the example and compiles it (g++ and
#                     clang++, warning-free) against the declaration-only ARGoS headers

.PHONY: bench-cpp argos-check

bench: bench-cpp

bench-cpp:
	$(PYTHON) benchmarks/cpp_steps.py

argos-check:
	$(SWARMVM) gen $(EXAMPLE) --target argos -o $(BUILD)/gen/argos --name energy_worker >/dev/null
	@for cxx in g++ clang++; do \
	  $$cxx -std=c++17 -Wall -Wextra -Werror -pedantic -Ifirmware/argos -I$(BUILD)/gen/argos \
	    -c $(BUILD)/gen/argos/energy_worker_controller.cpp -o $(BUILD)/gen/argos/energy_worker_controller.$$cxx.o \
	    || exit 1; echo "$$cxx: $(BUILD)/gen/argos/energy_worker_controller.cpp compiles"; done
