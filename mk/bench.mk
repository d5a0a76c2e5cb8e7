# swarmvm's minimal profile beside the published VM (issue 35, point 4; docs/figures.md).
#   make bench        also runs benchmarks/flash_vs_published.py: per corpus supervisor, on avr-gcc
#                     (ATmega328P) and arm-none-eabi-gcc (Cortex-M4F), the published-form VM
#                     (benchmarks/published_form/) and swarmvm's SVM_TRUSTED_IMAGE profile built
#                     side by side, their flash, RAM and cost per step (cycles in simavr on AVR,
#                     instructions counted in QEMU -icount on ARM, both VMs checked to take the
#                     same transitions), and the ratios
#   make bench-flash  that benchmark alone

.PHONY: bench-flash

bench: bench-flash

# Its own line names setup (not the Makefile's SET_UP_FIRST list, which another area owns).
bench-flash: setup
	$(PYTHON) benchmarks/flash_vs_published.py --json $(BUILD)/bench/flash_vs_published.json
