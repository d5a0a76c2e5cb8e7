# `make format-headers`: rewrite the C and C++ runtimes' copies of the image format's numbers
# (runtime_c/swarmvm_format.h, runtime_cpp/swarmvm_format.hpp) from runtime_py/swarmvm_format.py
# after a change of the format (scripts/format_headers.py); tests/compiler/test_format_headers.py
# fails while a committed copy differs from what it writes.

.PHONY: format-headers

format-headers: setup
	$(PYTHON) scripts/format_headers.py
