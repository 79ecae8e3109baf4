# `make reproduce-table`: the paper's Table 1 grid (issue 5), and
# build/imgmetrics (scripts/imgmetrics.c), the image-error tool it uses.
#
#   make reproduce-table                      # full grid: 1024x768, 2x2 samples, 3 repeats, 1 thread
#   make reproduce-table SIZE=256x192 REPEATS=1 PHOTONS="50000" NNS="10 100"
#   make reproduce-table THREADS=             # all cores (--threads 0)
#
# Knobs: SIZE (or WIDTH/HEIGHT), SUBPIXELS, PHOTONS, NNS, METHODS, REPEATS,
# THREADS, RESULTS (results dir), TABLE (output stem, default RESULTS/table1),
# TAG + PM_ARGS (+ CONV_CELLROOT) for a variant with extra render options,
# REF (reference EXR; default: found in reference/ by size, see
# experiments/table.sh), SCENE. Each cell is one make target,
# RESULTS/cells/<W>x<H>-s<S>-t<T>/<method>-p<P_e>-n<n>/summary-r<REPEATS>.tsv,
# beside the cell's per-repeat stats JSON and its image (first repeat), so an
# interrupted run resumes where it stopped (repeats already done are kept).
# Variables: experiments/config.mk.

CELLS := $(foreach p,$(PHOTONS),$(foreach n,$(NNS),$(foreach m,$(METHODS),$(m)-p$(p)-n$(n))))
CELL_FILES := $(foreach c,$(CELLS),$(CELLROOT)/$(c)/summary-r$(REPEATS).tsv)

# One cell: REPEATS renders of one (method, P_e, n).
$(CELLROOT)/%/summary-r$(REPEATS).tsv: | $(BUILD)/photonmap
	@PM=$(PM) PM_ARGS="$(PM_ARGS)" SCENE=$(SCENE) WIDTH=$(WIDTH) HEIGHT=$(HEIGHT) SUBPIXELS=$(SUBPIXELS) \
	  THREADS_ARG=$(T_ARG) CELL_LIST="$(CELLS)" bash experiments/cell.sh $* $(CELLROOT)/$* $(REPEATS)

.PHONY: reproduce-cells
reproduce-cells: $(CELL_FILES)
reproduce-table: $(CELL_FILES) | $(IMGMETRICS)
	@PM=$(PM) SCENE=$(SCENE) CELLROOT=$(CELLROOT) CONV_CELLROOT=$(CONV_CELLROOT) PM_ARGS="$(PM_ARGS)" PHOTONS="$(PHOTONS)" NNS="$(NNS)" METHODS="$(METHODS)" REPEATS=$(REPEATS) \
	  WIDTH=$(WIDTH) HEIGHT=$(HEIGHT) SUBPIXELS=$(SUBPIXELS) THREADS_LABEL="$(if $(strip $(THREADS)),$(strip $(THREADS)),all ($(shell nproc)))" \
	  REF="$(REF)" IMGMETRICS=$(IMGMETRICS) bash experiments/table.sh $(TABLE)
