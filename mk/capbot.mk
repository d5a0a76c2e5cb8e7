# CapBot (Cortex-M4F): generated Zephyr applications, built bare-metal for QEMU mps2-an386.
#   make firmware   also builds $(BUILD)/capbot/energy_worker.elf and .bin (the bundled example)
#   make emulate    runs that image in QEMU and shows its trace (mk/emulate.mk)
#   make bench      also runs benchmarks/m4_cycles.py (instructions per VM step in QEMU, current
#                   VM against the baseline, in one run)
#   make ... CAPBOT_CFLAGS=-DSVM_STACK_PAINT   images that print main's deepest stack at exit
# The control-logic flash page (firmware/capbot/swarmvm_logic_page.h, 4 KB at CAPBOT_LOGIC_PAGE):
#   $(BUILD)/capbot/<name>-logic.hex   a model's image at the page address, Intel HEX, for
#                                      nrfjprog --program / west flash --hex-file on the robot
#   $(BUILD)/capbot/logic-vm.elf       the example's application built with the page limits
#                                      (page_limits.flags): runs any model that fits them, e.g.
#                                      qemu ... -kernel logic-vm.elf -device loader,file=X.svm,addr=0xF3000,force-raw=on
# $(BUILD)/capbot/<name>.elf exists for the example and for every corpus supervisor (file stem):
# `swarmvm gen --target capbot` into $(BUILD)/capbot/gen/<name>/, then the Makefile gen writes into
# its qemu/ folder, as a user builds it (the generated src/ minus the Zephyr main.c, plus the copies
# of firmware/capbot/'s start-up code, linker script, CapBot API stand-ins and bare-metal main
# printing the trace through semihosting). The image is copied to $(BUILD)/capbot/ with what
# `swarmvm footprint` reads beside it: the project's sidecar, <name>.footprint.json (the
# declarations of its indirect calls), and the .su files, as <name>.elf-<source>.su.

.PHONY: capbot-firmware bench-m4

CAPBOT_FW := firmware/capbot
CAPBOT_CC ?= arm-none-eabi-gcc
CAPBOT_OBJCOPY ?= arm-none-eabi-objcopy
CAPBOT_QEMU ?= qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting-config enable=on,target=native
CAPBOT_FW_SOURCES := $(addprefix $(CAPBOT_FW)/,startup.c app_qemu.c capbot_qemu.c)
CAPBOT_LOGIC_PAGE := 0x000F3000
CAPBOT_FW_DEPS := $(CAPBOT_FW_SOURCES) $(addprefix $(CAPBOT_FW)/,capbot.h m4.flags mps2_an386.ld)
CAPBOT_GEN_DEPS := $(wildcard templates/capbot/*.j2 templates/c/*.j2 runtime_c/*.[ch] generator/*.py \
  generator/targets/capbot.py) $(CAPBOT_FW_DEPS)
CAPBOT_CORPUS := $(sort $(basename $(notdir $(wildcard tests/corpus/*/*.yaml))))
# Extra compiler flags of the <name>.elf images, e.g. -DSVM_STACK_PAINT (startup.c: main's deepest
# stack measured by painting, printed on stderr at exit).
CAPBOT_CFLAGS ?=
# What the indirect calls of these images reach, for `swarmvm footprint` of an image without the
# sidecar (docs/footprint.md, "Stack"; the sidecar declares the same, swarmvm.targets.capbot):
# the dispatch app_qemu.c gives the VM, the character sinks it gives the trace printer, and
# newlib's stdio writing a stream (its FILE's write and seek functions).
CAPBOT_INDIRECT := --indirect svm_step=svm_app_traced_dispatch --indirect svm_put_decimal=to_stdout,to_stderr \
  --indirect __sfvwrite_r=__swrite --indirect __sflush_r=__swrite,__sseek

firmware: capbot-firmware
bench: bench-m4

capbot-firmware: $(BUILD)/capbot/energy_worker.elf $(BUILD)/capbot/energy_worker.bin \
  $(BUILD)/capbot/logic-vm.elf $(BUILD)/capbot/energy_worker-logic.hex

bench-m4:
	$(PYTHON) benchmarks/m4_cycles.py --json $(BUILD)/bench/m4_cycles.json

$(BUILD)/capbot/%.bin: $(BUILD)/capbot/%.elf
	$(CAPBOT_OBJCOPY) -O binary $< $@

# The model's table image (written by `swarmvm gen` next to its application) moved to the page.
$(BUILD)/capbot/%-logic.hex: $(BUILD)/capbot/gen/%/CMakeLists.txt
	$(CAPBOT_OBJCOPY) -I binary -O ihex --change-addresses $(CAPBOT_LOGIC_PAGE) $(<D)/$*.svm $@

# The example's application with the page limits instead of the model's: the bare-metal sources,
# the example's src/ and the svm_app.h of its qemu/ (the compiled-in fallback it names).
$(BUILD)/capbot/logic-vm.elf: $(BUILD)/capbot/gen/energy_worker/CMakeLists.txt $(CAPBOT_FW_DEPS) $(CAPBOT_FW)/page_limits.flags
	$(CAPBOT_CC) @$(CAPBOT_FW)/m4.flags @$(CAPBOT_FW)/page_limits.flags -I$(<D)/qemu -I$(<D)/src -I$(CAPBOT_FW) \
	  -T $(CAPBOT_FW)/mps2_an386.ld $(CAPBOT_FW_SOURCES) $(filter-out %/main.c,$(wildcard $(<D)/src/*.c)) -o $@

# $(call capbot_rules,NAME,MODEL FILE): generate the application, build its bare-metal image with
# the generated qemu/Makefile (CAPBOT_CFLAGS as its CPPFLAGS), and copy it, its sidecar and its
# .su files to $(BUILD)/capbot/ (the .su files of an image as <name>.elf-<source>.su, the names
# one gcc command compiling and linking gives them, so the images sharing the folder keep theirs).
define capbot_rules
$(BUILD)/capbot/gen/$1/CMakeLists.txt: $2 $(CAPBOT_GEN_DEPS)
	$(SWARMVM) gen $2 --target capbot -o $(BUILD)/capbot/gen/$1 --name $1 >/dev/null

$(BUILD)/capbot/$1.elf: $(BUILD)/capbot/gen/$1/CMakeLists.txt
	$(MAKE) -s --no-print-directory -C $(BUILD)/capbot/gen/$1/qemu CC=$(CAPBOT_CC) CPPFLAGS="$(CAPBOT_CFLAGS)"
	rm -f $(BUILD)/capbot/$1.elf-*.su
	for su in $(BUILD)/capbot/gen/$1/qemu/*.su; do cp $$$$su $(BUILD)/capbot/$1.elf-$$$${su##*/}; done
	cp $(BUILD)/capbot/gen/$1/qemu/$1.footprint.json $(BUILD)/capbot/$1.footprint.json
	cp $(BUILD)/capbot/gen/$1/qemu/$1.elf $$@
endef

$(eval $(call capbot_rules,energy_worker,$(EXAMPLE)))
$(foreach n,$(filter-out energy_worker,$(CAPBOT_CORPUS)),\
  $(eval $(call capbot_rules,$n,$(firstword $(wildcard tests/corpus/*/$n.yaml)))))
