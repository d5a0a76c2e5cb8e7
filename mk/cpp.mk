# C++ runtime (runtime_cpp/); the ARGoS target's rules are in mk/argos.mk.
#   make bench        also runs the C++ steps-per-second benchmark (benchmarks/cpp_steps.py): the
#                     current VM against the baseline's (benchmarks/baseline.py), built side by side
#                     and the drop-in SCT (sct.h, exact mode) against the published sct.cpp

.PHONY: bench-cpp

bench: bench-cpp

bench-cpp:
	$(PYTHON) benchmarks/cpp_steps.py --json $(BUILD)/bench/cpp_steps.json
