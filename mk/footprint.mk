# `make footprint`: flash, static RAM and worst-case stack of every corpus supervisor on every C microcontroller
# target (Kilobot: mk/kilobot.mk's images; CapBot: mk/capbot.mk's), split into VM core, tables
# and application (docs/footprint.md), with the runtimes' source sizes (--runtime-sizes: the
# project's own figures, which a report on a user's images leaves out). Writes
# $(BUILD)/footprint.md and $(BUILD)/footprint.json and fails, with the report shown, when an
# image exceeds a limit, naming it. `make footprint STREAM=1` checks the Kilobot images built
# with streaming (footprint-stream.md).

.PHONY: footprint

FOOTPRINT_TARGETS := capbot kilobot
FOOTPRINT_NAMES := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))
FOOTPRINT_ELFS := $(foreach t,$(FOOTPRINT_TARGETS),$(FOOTPRINT_NAMES:%=$(if $(filter kilobot,$t),$(KILOBOT_OUT),$(BUILD)/$t)/%.elf))

FOOTPRINT_REPORT := $(BUILD)/footprint$(if $(filter 1,$(STREAM)),-stream)

footprint: setup $(FOOTPRINT_REPORT).md
	@cat $(FOOTPRINT_REPORT).md

# The Kilobot images are read where their generated Makefile built them, beside the .su files
# its -fstack-usage writes (the worst-case stack); FOOTPRINT_INDIRECT declares what the indirect
# calls of the Kilobot runtime and kilolib reach (docs/footprint.md, "Stack").
FOOTPRINT_READ := $(foreach e,$(FOOTPRINT_ELFS),$(if $(filter $(KILOBOT_OUT)/%,$e),$(KILOBOT_OUT)/gen/$(basename $(notdir $e))/$(notdir $e),$e))
FOOTPRINT_INDIRECT := --indirect svm_step=svm_kilobot_app_dispatch,dispatch --indirect kilo_start=setup,loop \
  --indirect __vector_14=message_tx,message_tx_success,message_tx_dummy,message_tx_success_dummy \
  --indirect __vector_23=on_message,message_rx_dummy

$(FOOTPRINT_REPORT).md: $(FOOTPRINT_ELFS) $(wildcard generator/footprint*.py)
	@$(SWARMVM) footprint $(FOOTPRINT_READ) $(FOOTPRINT_INDIRECT) --runtime-sizes --json $(FOOTPRINT_REPORT).json > $@ || { cat $@; rm -f $@; exit 1; }
