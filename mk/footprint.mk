# `make footprint`: flash and static RAM of every corpus supervisor on every C microcontroller
# target (Kilobot: mk/kilobot.mk's images; CapBot: mk/capbot.mk's), split into VM core, tables
# and application (docs/footprint.md). Writes $(BUILD)/footprint.md and $(BUILD)/footprint.json
# and fails, with the report shown, when an image exceeds a limit.

.PHONY: footprint

FOOTPRINT_TARGETS := capbot kilobot
FOOTPRINT_NAMES := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))
FOOTPRINT_ELFS := $(foreach t,$(FOOTPRINT_TARGETS),$(FOOTPRINT_NAMES:%=$(BUILD)/$t/%.elf))

footprint: $(BUILD)/footprint.md
	@cat $<

$(BUILD)/footprint.md: $(FOOTPRINT_ELFS) generator/footprint.py
	@$(SWARMVM) footprint $(FOOTPRINT_ELFS) --json $(BUILD)/footprint.json > $@ || { cat $@; rm -f $@; exit 1; }
