# Kilobot (ATmega328P): generated applications built with their generated Makefile against the
# real kilolib, with kilolib's own flags.
#   make kilolib    finds kilolib (KILOLIB=folder holding kilolib.h and build/kilolib.a) or builds
#                   it once from KILOLIB_SRC (default ../shared/vendor/kilolib-b95fdaf.tar.gz) into
#                   ${XDG_CACHE_HOME:-~/.cache}/swarmvm/ (firmware/kilobot/kilolib_build.py);
#                   `make test` and `make firmware` do it first
#   make firmware   also builds $(KILOBOT_OUT)/<name>.elf for the example (energy_worker, with
#                   its .hex) and every corpus supervisor (file stem): `swarmvm gen --target
#                   kilobot` into $(KILOBOT_OUT)/gen/<name>/, then that folder's Makefile with
#                   KILOLIB= and the project's warnings as errors. STREAM=1 builds the streaming
#                   variant into $(BUILD)/kilobot-stream/ (`make footprint STREAM=1` checks it).
#   make kilobot-board   the simavr Kilobot board (generator/footprint/kilobot_board/: the IR channel)
#   make emulate    runs the swap demo on the board (mk/emulate.mk)
#   make bench      also runs benchmarks/avr_cycles.py (cycles per VM step in simavr and the VM
#                   core's flash and RAM, current VM against the baseline, in one run)
# Whether an image fits the robot is `make footprint`'s verdict (mk/footprint.mk).

.PHONY: kilolib kilobot-firmware kilobot-board bench-avr

KILOBOT_WARNINGS := -Wextra -Werror -pedantic
KILOBOT_GEN_DEPS := $(wildcard templates/kilobot/*.j2 templates/c/*.j2 runtime_c/swarmvm*.[ch] generator/*.py)
KILOBOT_CORPUS := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))

firmware: kilobot-firmware
bench: bench-avr
test: kilolib kilobot-board

# Missing tools stop `make test` only in CI (CI=true); elsewhere the reason is printed and the
# Kilobot tests skip, saying how to get them.
kilolib:
	@printf 'kilolib: '; $(PYTHON) firmware/kilobot/kilolib_build.py || [ "$$CI" != true ]

kilobot-board:
	@printf 'kilobot board: '; $(PYTHON) firmware/kilobot/board.py || [ "$$CI" != true ]

kilobot-firmware: $(addprefix $(KILOBOT_OUT)/,$(KILOBOT_CORPUS:=.elf) energy_worker.hex)

bench-avr:
	$(PYTHON) benchmarks/avr_cycles.py --json $(BUILD)/bench/avr_cycles.json

$(KILOBOT_OUT)/%.hex: $(KILOBOT_OUT)/%.elf
	avr-objcopy -O ihex -R .eeprom -R .fuse -R .lock -R .signature $< $@

# $(call kilobot_rules,NAME,MODEL FILE)
define kilobot_rules
$(KILOBOT_OUT)/gen/$1/Makefile: $2 $(KILOBOT_GEN_DEPS)
	$(SWARMVM) gen $2 --target kilobot -o $(KILOBOT_OUT)/gen/$1 --name $1 >/dev/null

$(KILOBOT_OUT)/$1.elf: $(KILOBOT_OUT)/gen/$1/Makefile
	kilolib=$$$$($(PYTHON) firmware/kilobot/kilolib_build.py) && $(MAKE) -s --no-print-directory -C $(KILOBOT_OUT)/gen/$1 $1.elf \
	  KILOLIB="$$$$kilolib" STREAM=$(STREAM) CPPFLAGS="$(KILOBOT_WARNINGS)"
	cp $(KILOBOT_OUT)/gen/$1/$1.elf $$@
endef

$(eval $(call kilobot_rules,energy_worker,$(EXAMPLE)))
$(foreach n,$(filter-out energy_worker,$(KILOBOT_CORPUS)),\
  $(eval $(call kilobot_rules,$n,$(firstword $(wildcard tests/corpus/*/$n.yaml)))))
