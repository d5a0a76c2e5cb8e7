# `make emulate`: the bundled example (model energy_worker) on the emulated robots.
#   1. a generated Kilobot application in simavr receiving a new supervisor over its messages
#      (mk/kilobot_stream.mk: the trace switches at the swap), and the CapBot application
#      (mk/capbot.mk) in QEMU, first lines of its trace; the CapBot VM binary logic-vm.elf then
#      runs another supervisor (uav) written into its control-logic flash page
#      (firmware/capbot/swarmvm_logic_page.h) from $(BUILD)/capbot/uav-logic.hex;
#   2. one event script (`swarmvm script --steps $(EMULATE_STEPS) --seed $(EMULATE_SEED)`)
#      replayed through the conformance harnesses on simavr, QEMU, host C and host C++, each
#      trace diffed against `swarmvm trace` (the Python VM): one verdict line per target,
#      non-zero exit on any difference (firmware/emulate_example.py, work in $(BUILD)/emulate).

.PHONY: emulate

EMULATE_STEPS ?= 40
EMULATE_SEED ?= 1
EMULATE_LINES ?= 6

EMULATE_PAGE_MODEL ?= uav

emulate: setup $(BUILD)/capbot/energy_worker.elf $(BUILD)/capbot/logic-vm.elf $(BUILD)/capbot/$(EMULATE_PAGE_MODEL)-logic.hex
	@echo "== Kilobot application, simavr ATmega328P, given a new supervisor at run time:"
	@$(MAKE) -s --no-print-directory kilobot-swap-demo
	@echo "== CapBot application, QEMU mps2-an386 (step, events fired, states, violations):"
	@timeout 60 $(CAPBOT_QEMU) -kernel $(BUILD)/capbot/energy_worker.elf > $(BUILD)/capbot/energy_worker.trace \
	  2> $(BUILD)/capbot/energy_worker.log; status=$$?; cat $(BUILD)/capbot/energy_worker.log; \
	  head -n $(EMULATE_LINES) $(BUILD)/capbot/energy_worker.trace; \
	  [ $$status -eq 0 ] || { echo "QEMU exit status $$status"; exit 1; }
	@echo "== CapBot logic-vm.elf, $(EMULATE_PAGE_MODEL) in the flash page ($(EMULATE_PAGE_MODEL)-logic.hex):"
	@timeout 60 $(CAPBOT_QEMU) -kernel $(BUILD)/capbot/logic-vm.elf \
	  -device loader,file=$(BUILD)/capbot/$(EMULATE_PAGE_MODEL)-logic.hex 2>&1 | head -n 4
	@echo "== One event script on every runtime, compared with the Python VM:"
	@$(PYTHON) firmware/emulate_example.py $(EXAMPLE) --name energy_worker \
	  --steps $(EMULATE_STEPS) --seed $(EMULATE_SEED) --build $(BUILD)/emulate
