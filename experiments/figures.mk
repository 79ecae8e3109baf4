# figures.mk: the rule of `make figures`: PNGs in RESULTS/figures/ from the
# FIG_SIZE grid of `make reproduce-table` (issue 5): Figure 3 with the
# reference and error maps, the speed-accuracy trade-off, time vs n and vs
# P_e, crops where the methods differ most; images of the paper estimate,
# first seed. Run `make reproduce-table` (and `make resolution` for the
# fallback reference) first; see experiments/figures.sh.
figures: | $(BUILD)/imgmetrics
	@RESULTS=$(RESULTS) RUNROOT=$(RESULTS)/runs/$(SCENE_NAME)-$(FIG_SIZE)-s$(SUBPIXELS)-$(T_LABEL) FIG_SIZE=$(FIG_SIZE) \
	  FIG_SEED=$(firstword $(SEED_LIST)) TABLE_CSV=$(TABLE).csv REFHIGH=$(RES_REF_DIR)/$(FIG_SIZE).exr \
	  RES_REF_PHOTONS=$(RES_REF_PHOTONS) RES_REF_NN=$(RES_REF_NN) PYTHON=$(PYTHON) \
	  bash experiments/figures.sh
