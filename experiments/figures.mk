# `make figures`: PNGs in RESULTS/figures/ from the full-size grid of
# `make reproduce-table` (issue 5): Figure 3 with the reference and error
# maps, the speed-accuracy trade-off, time vs n and vs P_e, crops where the
# methods differ most. Run `make reproduce-table` (and `make resolution` for
# the fallback reference) first; see experiments/figures.sh.
figures: | $(BUILD)/imgmetrics
	@RESULTS=$(RESULTS) CELLROOT=$(RESULTS)/cells/$(FIG_SIZE)-s$(SUBPIXELS)-$(T_LABEL) FIG_SIZE=$(FIG_SIZE) \
	  TABLE_CSV=$(TABLE).csv RES_REF_PHOTONS=$(RES_REF_PHOTONS) RES_REF_NN=$(RES_REF_NN) \
	  bash experiments/figures.sh
