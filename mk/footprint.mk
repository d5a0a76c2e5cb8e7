# `make footprint`: flash, static RAM and worst-case stack of every corpus supervisor on every C microcontroller
# target (Kilobot: mk/kilobot.mk's images; CapBot: mk/capbot.mk's), split into VM core, tables
# and application (docs/footprint.md), with the runtimes' source sizes (--runtime-sizes: the
# project's own figures, which a report on a user's images leaves out). Writes
# $(BUILD)/footprint.md and $(BUILD)/footprint.json and fails, with the report shown, when an
# image exceeds a limit, naming it. `make footprint STREAM=1` checks the Kilobot images built
# with streaming (footprint-stream.md).
# Then, as a user's CI does it (docs/footprint.md, "The project's own CI"), the bundled example's
# Kilobot image with the event script `make emulate` replays (cycles per step) against the baseline
# kept in the repository, FOOTPRINT_BASELINE: the delta is printed, and the command fails only on
# the project's budgets (FOOTPRINT_BUDGET: [tool.swarmvm.footprint] of pyproject.toml) and on a
# figure grown by more than FOOTPRINT_GROWTH per cent (why 10: docs/footprint.md).
#   make footprint-example    that comparison alone
#   make footprint-baseline   writes the baseline again (after an intended change or a toolchain update)

.PHONY: footprint footprint-example footprint-baseline

FOOTPRINT_TARGETS := capbot kilobot
FOOTPRINT_NAMES := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))
FOOTPRINT_ELFS := $(foreach t,$(FOOTPRINT_TARGETS),$(FOOTPRINT_NAMES:%=$(if $(filter kilobot,$t),$(KILOBOT_OUT),$(BUILD)/$t)/%.elf))

FOOTPRINT_REPORT := $(BUILD)/footprint$(if $(filter 1,$(STREAM)),-stream)
FOOTPRINT_BASELINE ?= benchmarks/footprint-baseline.json
FOOTPRINT_BUDGET ?= pyproject.toml
FOOTPRINT_GROWTH ?= 10
FOOTPRINT_EVENTS := $(BUILD)/footprint-events.txt

footprint: setup $(FOOTPRINT_REPORT).md $(if $(filter 1,$(STREAM)),,$(FOOTPRINT_EVENTS))
	@cat $(FOOTPRINT_REPORT).md
	$(if $(filter 1,$(STREAM)),,@$(FOOTPRINT_COMPARE))

# The Kilobot images are read where their generated Makefile built them, beside the .su files
# its -fstack-usage writes (the worst-case stack), the CapBot ones where mk/capbot.mk put them
# beside the .su files of their generated qemu/ build. No --indirect: what the indirect calls of
# each image reach is in the sidecar gen wrote beside it (docs/footprint.md, "Sidecars"; the
# Kilobot's also in its target's record), so every limit, the stack's included, is checked.
FOOTPRINT_READ := $(foreach e,$(FOOTPRINT_ELFS),$(if $(filter $(KILOBOT_OUT)/%,$e),$(KILOBOT_OUT)/gen/$(basename $(notdir $e))/$(notdir $e),$e))

$(FOOTPRINT_REPORT).md: $(FOOTPRINT_ELFS) $(wildcard generator/footprint/*.py)
	@$(SWARMVM) footprint $(FOOTPRINT_READ) --runtime-sizes --json $(FOOTPRINT_REPORT).json > $@ || { cat $@; rm -f $@; exit 1; }

FOOTPRINT_EXAMPLE := $(SWARMVM) footprint $(KILOBOT_OUT)/gen/energy_worker/energy_worker.elf \
  --cycles $(FOOTPRINT_EVENTS) --budget $(FOOTPRINT_BUDGET)
FOOTPRINT_COMPARE = echo "== The bundled example against $(FOOTPRINT_BASELINE):" && \
  $(FOOTPRINT_EXAMPLE) --baseline $(FOOTPRINT_BASELINE) --fail-on-growth $(FOOTPRINT_GROWTH)

footprint-example footprint-baseline: setup $(KILOBOT_OUT)/energy_worker.elf $(FOOTPRINT_EVENTS)
footprint-example:
	@$(FOOTPRINT_COMPARE)
footprint-baseline:
	$(FOOTPRINT_EXAMPLE) --json $(FOOTPRINT_BASELINE)

# The event script `make emulate` replays (mk/emulate.mk's steps and seed).
$(FOOTPRINT_EVENTS): $(EXAMPLE) $(wildcard generator/*.py)
	@mkdir -p $(@D)
	$(SWARMVM) script $(EXAMPLE) --steps $(EMULATE_STEPS) --seed $(EMULATE_SEED) > $@
