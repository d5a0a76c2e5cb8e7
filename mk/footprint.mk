# `make footprint`: flash and static RAM of every corpus supervisor on every C microcontroller
# target (Kilobot: mk/kilobot.mk's images; CapBot: mk/capbot.mk's), split into VM core, tables
# and application (docs/footprint.md). Writes $(BUILD)/footprint.md and $(BUILD)/footprint.json
# and fails, with the report shown, when an image exceeds a limit, naming it. `make footprint
# STREAM=1` checks the Kilobot images built with streaming (footprint-stream.md).

.PHONY: footprint

FOOTPRINT_TARGETS := capbot kilobot
FOOTPRINT_NAMES := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))
FOOTPRINT_ELFS := $(foreach t,$(FOOTPRINT_TARGETS),$(FOOTPRINT_NAMES:%=$(if $(filter kilobot,$t),$(KILOBOT_OUT),$(BUILD)/$t)/%.elf))

FOOTPRINT_REPORT := $(BUILD)/footprint$(if $(filter 1,$(STREAM)),-stream)

footprint: $(FOOTPRINT_REPORT).md
	@cat $<

$(FOOTPRINT_REPORT).md: $(FOOTPRINT_ELFS) generator/footprint.py
	@$(SWARMVM) footprint $(FOOTPRINT_ELFS) --json $(FOOTPRINT_REPORT).json > $@ || { cat $@; rm -f $@; exit 1; }
