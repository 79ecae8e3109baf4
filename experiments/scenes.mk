# scenes.mk: the rules of `make scenes`, the cross-scene study (issue 12).
# For every scene in SCENES, runs the Table 1 grid (both methods, both
# estimates, SCENES_SEEDS seeds) at SCENES_SIZE against our own converged
# render of that scene (the high-photon reference of `make resolution`,
# RES_REF_PHOTONS photons, n = RES_REF_NN, corrected estimate), then
# experiments/analysis/scenes.py writes RESULTS/scenes.md (per scene: the
# equal-error speed-up, the share of the conventional time spent in the
# kNN, where the precomputed method's error lies) and a difference image per
# scene in RESULTS/figures/. Per scene, the grid's files are
# RESULTS/scenes/{table,runs,cells,equal-error}-<scene>.* and its renders
# RESULTS/runs/<scene>-<size>-... (the same layout as reproduce-table).
# Variables: experiments/config.mk.

scenes: | $(BUILD)/photonmap
	@MAKE="$(MAKE)" RESULTS=$(RESULTS) SCENES="$(SCENES)" SCENES_SIZE=$(SCENES_SIZE) SCENES_SEEDS="$(SCENES_SEEDS)" \
	  SCENES_CELL=$(SCENES_CELL) PHOTONS="$(PHOTONS)" NNS="$(NNS)" METHODS="$(METHODS)" ESTIMATES="$(ESTIMATES)" \
	  THREADS="$(THREADS)" PM=$(PM) SUBPIXELS=$(SUBPIXELS) EE_TIME=$(EE_TIME) PYTHON=$(PYTHON) \
	  RES_REF_PHOTONS=$(RES_REF_PHOTONS) RES_REF_NN=$(RES_REF_NN) RES_REF_SEED=$(RES_REF_SEED) bash experiments/scenes.sh
