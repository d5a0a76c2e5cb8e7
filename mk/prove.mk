# `make prove` (issue 41, docs/proof.md): Frama-C's Eva over the C runtime from the harnesses of
# tests/proof/ (the VM core, stream receiver, logic page, learned policy, store, Kilobot glue and
# Nadzoru C API), one configuration per target build of each (tests/proof/prove.py's CONFIGS:
# limits, features, the target's int and pointer sizes; sixteen by default), then WP on the
# image checks that Eva cannot prove (tests/proof/wp_units.py: one run per distinct build of
# them; CVC4 and Z3 through Why3), about four minutes on two cores; the properties neither
# proves are compared with the checked-in list tests/proof/alarms.txt: a new alarm fails, and
# so does a listed one that is gone.
# PROVE_CONFIGS="host kilobot" runs some; `make prove-update` rewrites the list (classifications
# of the lines that stay are kept, new lines come in unclassified). frama-c-base, why3, cvc4 and
# z3: scripts/setup.sh.

PROVE_CONFIGS ?=
PROVE_ARGS = $(foreach c,$(PROVE_CONFIGS),--config $(c))

.PHONY: prove prove-update

prove: setup
	$(PYTHON) tests/proof/prove.py --work $(BUILD)/proof $(PROVE_ARGS)

prove-update: setup
	$(PYTHON) tests/proof/prove.py --work $(BUILD)/proof $(PROVE_ARGS) --update
