# caustic.mk: the rule of `make caustic`: the Figure 3 cells' photon counts
# and n rendered on the caustic scene through the table machinery
# (`make reproduce-table` with SCENE=CAUSTIC_SCENE at CAUSTIC_SIZE, its own
# runs directory and CAUSTIC-{runs,cells,table1,equal-error}.*), then
# experiments/analysis/caustic.py measures the caustic window: CAUSTIC.md,
# CAUSTIC.csv and FIGURES/caustic.png. Variables: experiments/config.mk.

CAUSTIC_W = $(word 1,$(subst x, ,$(CAUSTIC_SIZE)))
CAUSTIC_H = $(word 2,$(subst x, ,$(CAUSTIC_SIZE)))
CAUSTIC_REF_FILE = $(or $(CAUSTIC_REF),$(shell bash experiments/findref.sh $(CAUSTIC_SIZE) $(CAUSTIC_SCENE)))

caustic:
	$(if $(CAUSTIC_SCENE),,$(error caustic: no caustic scene (scenes/caustic.scene or reference/caustic.scene); set CAUSTIC_SCENE))
	$(if $(CAUSTIC_REF_FILE),,$(error caustic: no POV-Ray reference of $(CAUSTIC_SCENE) at $(CAUSTIC_SIZE) in reference/; set CAUSTIC_REF))
	@$(MAKE) --no-print-directory reproduce-table SCENE=$(CAUSTIC_SCENE) SIZE=$(CAUSTIC_SIZE) WIDTH=$(CAUSTIC_W) \
	  HEIGHT=$(CAUSTIC_H) PHOTONS="$(CAUSTIC_PHOTONS)" NNS="$(CAUSTIC_NNS)" SEEDS=$(CAUSTIC_SEEDS) \
	  SEED_LIST="$(shell seq 1 $(CAUSTIC_SEEDS))" TAG= PM_ARGS= METHODS="conventional precomputed" \
	  REF=$(CAUSTIC_REF_FILE) TABLE=$(CAUSTIC)-table1 RUNS_CSV=$(CAUSTIC)-runs.csv \
	  CELLS_CSV=$(CAUSTIC)-cells.csv EQUAL_ERROR=$(CAUSTIC)-equal-error
	@$(PYTHON) -m experiments.analysis.caustic --runs $(CAUSTIC)-runs.csv --ref $(CAUSTIC_REF_FILE) \
	  --window $(CAUSTIC_WINDOW) --window-at $(CAUSTIC_WINDOW_AT) --cells "$(FIG3_CELLS)" --out $(CAUSTIC) \
	  --figure $(FIGURES)/caustic.png
