# `make resolution`: beyond the paper (issue 5). For each output size in
# RES_SIZES, runs the Table 1 grid at that size (cells shared with
# `make reproduce-table`) and finds the cheapest (P_e, n, method) whose error
# against the reference stays under each target in RES_TARGETS (relMSE);
# writes RESULTS/resolution.md (+ RESULTS/resolution/table-<size>.csv|md).
# Reference per size (RES_REF): "ours" (default) is our own high-photon
# conventional render (RES_REF_PHOTONS emitted, RES_REF_NN nearest, all
# cores) at every size, so that the error targets mean the same at every
# size: POV-Ray references exist only at some sizes, and POV's radiosity
# differs from a converged photon map by a few percent (reference/ notes),
# which would floor relMSE at a size-dependent level. "pov" uses the POV-Ray
# render of that size in reference/ where there is one (else ours).

# Our high-photon reference at one size (stem = WxH).
$(RESULTS)/cells/%-refhigh-p$(RES_REF_PHOTONS)-n$(RES_REF_NN)/image.exr: | $(BUILD)/photonmap
	@mkdir -p $(dir $@)
	@echo "reference: conventional P_e=$(RES_REF_PHOTONS) n=$(RES_REF_NN) at $*, all cores"
	$(PM) render $(SCENE) --method conventional --photons $(RES_REF_PHOTONS) --nn $(RES_REF_NN) \
	  --width $(word 1,$(subst x, ,$*)) --height $(word 2,$(subst x, ,$*)) --subpixels $(SUBPIXELS) --threads 0 \
	  -o $@ --png $(dir $@)image.png --stats $(dir $@)stats.json --quiet

resolution: | $(BUILD)/imgmetrics $(BUILD)/photonmap
	@MAKE="$(MAKE)" RESULTS=$(RESULTS) RES_SIZES="$(RES_SIZES)" RES_TARGETS="$(RES_TARGETS)" \
	  RES_REF_PHOTONS=$(RES_REF_PHOTONS) RES_REF_NN=$(RES_REF_NN) RES_REPEATS=$(RES_REPEATS) RES_REF=$(RES_REF) \
	  PHOTONS="$(PHOTONS)" NNS="$(NNS)" THREADS="$(THREADS)" PM=$(PM) \
	  bash experiments/resolution.sh
