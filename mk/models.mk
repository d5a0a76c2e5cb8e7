# From models to firmware without a GUI (docs/models.md):
#   make models   synthesise the energy worker from its plants and specifications
#                 ($(MODELS_SRC), with libFAUDES), show it is equivalent to the bundled example,
#                 check its design properties and draw it, all into $(BUILD)/models/.

.PHONY: models

MODELS_SRC := tests/corpus/synthesis/energy_worker

models:
	$(SWARMVM) synth --script $(MODELS_SRC)/script.txt $(sort $(wildcard $(MODELS_SRC)/[GE]?.xml)) \
	  -o $(BUILD)/models/energy_worker.yaml
	$(SWARMVM) equiv $(BUILD)/models/energy_worker.yaml $(EXAMPLE)
	$(SWARMVM) check --properties $(BUILD)/models/energy_worker.yaml
	$(SWARMVM) export $(BUILD)/models/energy_worker.yaml --format svg -o $(BUILD)/models/pictures
