# `make fuzz`: the long fuzzing run (docs/fuzzing.md). Every fuzzer for FUZZ_SECONDS each (600
# by default; FUZZERS="yaml c_runtime" to run some): atheris over each reader (supervisor YAML,
# Nadzoru 2 XML, IDES .xmd, Nadzoru .nza, libFAUDES .gen, the .svm readers, event scripts) and
# over `gen` for every target with the code compiled, libFuzzer with AddressSanitizer and
# UndefinedBehaviorSanitizer over the C runtime's reader and step. Corpora grow in
# $(FUZZ_DIR)/<fuzzer>/corpus from run to run; findings land in $(FUZZ_DIR)/<fuzzer>/findings
# and fail the run. `make test` runs the short run (tests/fuzz/test_fuzz_short.py).

FUZZ_SECONDS ?= 600
FUZZ_DIR ?= $(BUILD)/fuzz
FUZZERS ?=

.PHONY: fuzz

fuzz: setup
	$(PYTHON) tests/fuzz/campaign.py --seconds $(FUZZ_SECONDS) --work $(FUZZ_DIR) $(FUZZERS)
