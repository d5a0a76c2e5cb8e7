# Learning (docs/learning.md): the learned-policy benchmark with its plot, and the size of the
# learning code on the Kilobot's MCU. Its emulator checks (C classifier and policy in simavr)
# are tests: `make test` runs them (tests/learning/).

.PHONY: bench-learning learning-size

bench: bench-learning

bench-learning:
	$(PYTHON) benchmarks/learning.py

# Flash and RAM of the learning code alone on the Kilobot's MCU (object file, -Os).
learning-size:
	@mkdir -p $(BUILD)/learning
	avr-gcc -mmcu=atmega328p -Os -funsigned-char -funsigned-bitfields -fpack-struct -fshort-enums \
	  -DF_CPU=8000000 -std=c99 -Wall -Wextra -Werror -pedantic -DSVM_MAX_EVENTS=32 -DSVM_MAX_SUPERVISORS=8 \
	  -Iruntime_c -c runtime_c/swarmvm_learn.c -o $(BUILD)/learning/swarmvm_learn.o
	avr-size -A $(BUILD)/learning/swarmvm_learn.o
