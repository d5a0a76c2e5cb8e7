# `make mutation`: mutation testing over the core modules (docs/mutation.md). cosmic-ray (the
# `mutation` extra) mutates a copy of the tree in $(MUTATION_DIR)/tree, never the checkout, one
# module at a time with the quick tests that cover it (tests/mutation/modules.toml), one worker;
# then $(MUTATION_DIR)/report.md and report.json, and exit status 1 when a module kills under 97 %
# of its mutants (equivalent ones, tests/mutation/equivalents.toml, set aside). Hours, not minutes:
# like the benchmarks, not part of `make test`. MUTATION_MODULES="runtime_py/swarmvm_vm.py" runs some.

MUTATION_DIR ?= $(BUILD)/mutation
MUTATION_MODULES ?=

.PHONY: mutation

mutation: setup
	$(PYTHON) -c "import cosmic_ray" 2>/dev/null || $(PYTHON) -m pip install -q -e '.[mutation]'
	nice -n 10 $(PYTHON) scripts/mutation.py --work $(MUTATION_DIR) $(foreach m,$(MUTATION_MODULES),--module $(m))

# `make mutation-c`: the same for the C runtime, runtime_c/swarmvm.c (scripts/mutation_c.py: its
# own mutants, judged by the quick host tests that compile it), in $(MUTATION_C_DIR); resumes an
# interrupted run. MUTATION_C_EVERY=K runs a 1-in-K sample. `make mutation-report` rewrites
# $(MUTATION_DIR)/report.md with the C runtime's row beside the Python modules'.

MUTATION_C_DIR ?= $(BUILD)/mutation-c
MUTATION_C_EVERY ?= 1

.PHONY: mutation-c mutation-report

mutation-c: setup
	nice -n 10 $(PYTHON) scripts/mutation_c.py --work $(MUTATION_C_DIR) --every $(MUTATION_C_EVERY)

mutation-report: setup
	$(PYTHON) scripts/mutation_report.py $(MUTATION_DIR) --also $(MUTATION_C_DIR) --equivalents tests/mutation/equivalents.toml
