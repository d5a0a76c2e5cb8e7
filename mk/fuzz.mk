# `make fuzz`: the long fuzzing run (docs/fuzzing.md). Every fuzzer for FUZZ_SECONDS each (600
# by default; FUZZERS="yaml c_runtime" to run some): atheris over each reader (supervisor YAML,
# Nadzoru 2 XML, IDES .xmd, Nadzoru .nza, libFAUDES .gen, the .svm readers, event scripts) and
# over `gen` for every target with the code compiled, libFuzzer with AddressSanitizer and
# UndefinedBehaviorSanitizer over the C runtime's reader and step. Corpora grow in
# $(FUZZ_DIR)/<fuzzer>/corpus from run to run; findings land in $(FUZZ_DIR)/<fuzzer>/findings
# and fail the run. Then the trust boundary's generative tests (user text through every
# target, the escaping functions, the readers, output under injected faults: docs/security.md)
# with hypothesis's long profile. `make test` runs the short run of both
# (tests/fuzz/test_fuzz_short.py; the same tests with the ci profile).

FUZZ_SECONDS ?= 600
FUZZ_DIR ?= $(BUILD)/fuzz
FUZZERS ?=

.PHONY: fuzz

fuzz: setup
	$(PYTHON) tests/fuzz/campaign.py --seconds $(FUZZ_SECONDS) --work $(FUZZ_DIR) $(FUZZERS)
	HYPOTHESIS_PROFILE=long $(PYTHON) -m pytest $(TRUST_BOUNDARY_TESTS)

TRUST_BOUNDARY_TESTS = tests/boundary tests/properties/test_hostile_text.py tests/cli/test_terminal_escaping.py
