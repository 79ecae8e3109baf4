# resolution.mk: the rules of `make resolution`, beyond the paper (issue 5).
# For each output size in RES_SIZES, runs the Table 1 grid at that size with
# RES_SEEDS seeds (renders shared with `make reproduce-table` of that size)
# and finds the cheapest (method, estimate, P_e, n) whose relMSE against the
# reference stays under each target in RES_TARGETS at 95% confidence; writes
# RESULTS/resolution.md and, per size, RESULTS/resolution/{table,runs,cells,
# equal-error}-<size>.* (experiments/resolution.sh, analysis/resolution.py).
# Reference per size (RES_REF): "ours" (default) is our own high-photon
# conventional render (corrected estimate) (RES_REF_PHOTONS emitted, RES_REF_NN nearest, all
# cores, --seed RES_REF_SEED, a seed no grid render uses) at every size, so that the error targets mean the same at
# every size: POV-Ray references exist only at some sizes, and POV's
# radiosity differs from a converged photon map by a few percent (reference/
# notes), which would floor relMSE at a size-dependent level. "pov" uses the
# POV-Ray render of that size in reference/ where there is one (else ours).

# Our high-photon reference at one size (stem = WxH): the corrected
# conventional estimate (unbiased; the paper's would be n/(n-1) = 0.5% high).
print-res-ref-dir:
	@echo $(RES_REF_DIR)
$(RES_REF_DIR)/%.exr: | $(BUILD)/photonmap
	$(if $(filter $(RES_REF_SEED),$(SEED_LIST) $(shell seq 1 $(RES_SEEDS)) $(shell seq 1 $(SCENES_SEEDS))),\
	  $(error RES_REF_SEED=$(RES_REF_SEED) is one of the grid's seeds: the reference would share photon paths with the renders it judges))
	@mkdir -p $(dir $@)
	@echo "reference: $(SCENE), conventional, corrected, P_e=$(RES_REF_PHOTONS) n=$(RES_REF_NN) at $*, all cores"
	$(PM) render $(SCENE) --method conventional --bias-correction --photons $(RES_REF_PHOTONS) --nn $(RES_REF_NN) \
	  --seed $(RES_REF_SEED) --width $(word 1,$(subst x, ,$*)) --height $(word 2,$(subst x, ,$*)) --subpixels $(SUBPIXELS) --threads 0 \
	  -o $@ --png $(@:.exr=.png) --stats $(@:.exr=.stats.json) --quiet

resolution: | $(BUILD)/photonmap
	@MAKE="$(MAKE)" RESULTS=$(RESULTS) RES_SIZES="$(RES_SIZES)" RES_TARGETS="$(RES_TARGETS)" \
	  RES_REF_PHOTONS=$(RES_REF_PHOTONS) RES_REF_NN=$(RES_REF_NN) RES_REF_SEED=$(RES_REF_SEED) RES_SEEDS="$(RES_SEEDS)" RES_REF=$(RES_REF) \
	  RES_REF_DIR=$(RES_REF_DIR) PHOTONS="$(PHOTONS)" NNS="$(NNS)" METHODS="$(METHODS)" ESTIMATES="$(ESTIMATES)" \
	  THREADS="$(THREADS)" PM=$(PM) SCENE=$(SCENE) EE_TIME=$(EE_TIME) PYTHON=$(PYTHON) \
	  bash experiments/resolution.sh
