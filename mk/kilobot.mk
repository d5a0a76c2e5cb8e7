# Kilobot (ATmega328P, kilolib): generated applications linked with the official flags.
#   make firmware   also builds $(BUILD)/kilobot/energy_worker.elf and .hex (the bundled example)
#   make emulate    runs that image in simavr (mk/emulate.mk)
#   make bench      also runs benchmarks/avr_cycles.py (cycles per VM step in simavr)
# $(BUILD)/kilobot/<name>.elf exists for the example and for every corpus supervisor (file
# stem): `swarmvm gen --target kilobot` into $(BUILD)/kilobot/gen/<name>/, compiled with the
# model's limit and source flags from the generated Makefile, against firmware/kilobot/
# (declaration-only kilolib.h, emulator-only kilolib_emu.c). An image over 28,672 bytes of
# flash fails the build.

.PHONY: kilobot-firmware bench-avr

KILOBOT_FW := firmware/kilobot
KILOBOT_CC ?= avr-gcc
KILOBOT_FLAGS := -mmcu=atmega328p -O3 -funsigned-char -funsigned-bitfields -fpack-struct -fshort-enums \
  -DF_CPU=8000000 -std=c99 -Wall -Wextra -Werror -pedantic
KILOBOT_FLASH := 28672
KILOBOT_GEN_DEPS := $(wildcard templates/kilobot/*.j2 templates/c/*.j2 runtime_c/swarmvm*.[ch] generator/*.py)
KILOBOT_CORPUS := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))

firmware: kilobot-firmware
bench: bench-avr

kilobot-firmware: $(BUILD)/kilobot/energy_worker.elf $(BUILD)/kilobot/energy_worker.hex

bench-avr:
	$(PYTHON) benchmarks/avr_cycles.py --json $(BUILD)/bench/avr_cycles.json

$(BUILD)/kilobot/%.hex: $(BUILD)/kilobot/%.elf
	avr-objcopy -O ihex -R .eeprom $< $@

# $(call kilobot_rules,NAME,MODEL FILE)
define kilobot_rules
$(BUILD)/kilobot/gen/$1/Makefile: $2 $(KILOBOT_GEN_DEPS)
	$(SWARMVM) gen $2 --target kilobot -o $(BUILD)/kilobot/gen/$1 --name $1 >/dev/null

$(BUILD)/kilobot/$1.elf: $(BUILD)/kilobot/gen/$1/Makefile $(KILOBOT_FW)/kilolib.h $(KILOBOT_FW)/kilolib_emu.c
	$(KILOBOT_CC) $(KILOBOT_FLAGS) $$$$(grep -o -- '-DSVM_[A-Z_]*=[A-Z_0-9]*' $$<) -I$(KILOBOT_FW) \
	  $$(addprefix $(BUILD)/kilobot/gen/$1/,$1_app.c $1_controller.c $1_tables.c swarmvm.c) \
	  $(KILOBOT_FW)/kilolib_emu.c -o $$@
	@flash=$$$$(avr-size -A $$@ | awk '/^\.(text|data) /{s+=$$$$2} END{print s}'); \
	  [ $$$$flash -le $(KILOBOT_FLASH) ] || { echo "$$@: $$$$flash B of flash, over the Kilobot's $(KILOBOT_FLASH) B"; rm -f $$@; exit 1; }
endef

$(eval $(call kilobot_rules,energy_worker,$(EXAMPLE)))
$(foreach n,$(filter-out energy_worker,$(KILOBOT_CORPUS)),\
  $(eval $(call kilobot_rules,$n,$(firstword $(wildcard tests/corpus/*/$n.yaml)))))
