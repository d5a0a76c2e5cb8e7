# Kilobot image streaming (docs/image-format.md, "Streaming an image").
#   make kilobot-swap-demo   runs hitl_leader's Kilobot application (real kilolib) in simavr on
#                            the Kilobot board (firmware/kilobot/board.py), streams
#                            network_leader into it over messages (first with a corrupted chunk,
#                            refused, then intact) and prints the trace changing at the swap,
#                            checked against the Python reference VM
#                            (tests/kilobot_stream_demo.py; built in $(BUILD)/kilobot/swap_demo/).

.PHONY: kilobot-swap-demo

kilobot-swap-demo:
	@$(PYTHON) tests/kilobot_stream_demo.py $(BUILD)/kilobot/swap_demo
