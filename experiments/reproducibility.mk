# reproducibility.mk: `make reproducibility`: the Table-1 grid of SCENE
# rendered twice, runs A and B, interleaved in time, and how far the two runs'
# paired results lie apart (experiments/analysis/reproducibility.py ->
# REPRO_DIR/reproducibility.{md,csv}). Knobs (experiments/config.mk): SIZE
# (default here 512x384), SEEDS, PHOTONS, NNS, ESTIMATES, REF; REPRO_TASKSET:
# a CPU list for taskset (empty: no pinning).
#
# Interleaving: the pairs (experiments/pair.sh: conventional and precomputed
# back to back) are rendered in one sequence, pair k of run A then pair k of
# run B, with A first at odd k and B first at even k, so that a slow phase of
# the machine falls on both runs alike; the two runs are otherwise two
# independent studies (their own run roots, collect and table), exactly as
# `make reproduce-table` twice would be. A pair already rendered (both
# records present) is kept: the target resumes.

repro_size = $(call knob,SIZE,$(REPRO_SIZE_DEFAULT))
define repro_study
repro-$(1)_SCENE = $$(SCENE)
repro-$(1)_SIZE = $$(repro_size)
repro-$(1)_SEEDS = $$(SEEDS)
repro-$(1)_PHOTONS = $$(PHOTONS)
repro-$(1)_NNS = $$(NNS)
repro-$(1)_METHODS = conventional precomputed
repro-$(1)_ESTIMATES = $$(ESTIMATES)
repro-$(1)_TAG = repro-$(1)
repro-$(1)_REF = $$(or $$(REF),$$(shell bash experiments/findref.sh $$(repro_size) $$(SCENE)))
repro-$(1)_REF_FAST = $$(if $$(REF),$$(REF_FAST),$$(shell bash experiments/findref.sh --fast $$(repro_size) $$(SCENE)))
repro-$(1)_NO_REF = no POV-Ray reference of $$(SCENE) at $$(repro_size) in reference/$$(SCENE_NAME)/: give REF=FILE.exr
repro-$(1)_RUNS_CSV = $$(REPRO_DIR)/runs-$(1).csv
repro-$(1)_CELLS_CSV = $$(REPRO_DIR)/cells-$(1).csv
repro-$(1)_TABLE = $$(REPRO_DIR)/table1-$(1)
repro-$(1)_EQUAL_ERROR = $$(REPRO_DIR)/equal-error-$(1)
$$(eval $$(call study,repro-$(1)))
endef
$(foreach r,a b,$(eval $(call repro_study,$(r))))

# the pair names (ESTIMATE-pP-nN/seedK) in the grid's order, seeds outermost
repro_pairs = $(call run_names,$(call run_cells,$(PHOTONS),$(NNS),x,$(ESTIMATES)),$(call seeds,$(SEEDS)))
repro_taskset = $(if $(strip $(REPRO_TASKSET)),taskset -c $(strip $(REPRO_TASKSET)))

.PHONY: reproducibility reproducibility-runs
reproducibility-runs: | $(BUILD)/photonmap $(DEPS_TEST)
	$(if $(repro-a_REF),,$(error reproducibility: $(repro-a_NO_REF)))
	@k=0; for p in $(patsubst x-%,%,$(repro_pairs)); do k=$$((k + 1)); \
	  if [ $$((k % 2)) -eq 1 ]; then order="a b"; else order="b a"; fi; \
	  for r in $$order; do \
	    if [ "$$r" = a ]; then root=$(repro-a_RUNROOT); list="$(repro-a_RUN_NAMES)"; \
	    else root=$(repro-b_RUNROOT); list="$(repro-b_RUN_NAMES)"; fi; \
	    [ -f $$root/conventional-$$p.run.json ] && [ -f $$root/precomputed-$$p.run.json ] && continue; \
	    echo "reproducibility: run $$r pair $$k: $$p"; \
	    PM=$(PM) PM_ARGS="" SCENE=$(SCENE) WIDTH=$(call size_w,$(repro_size)) HEIGHT=$(call size_h,$(repro_size)) \
	      SUBPIXELS=$(SUBPIXELS) THREADS_ARG=$(T_ARG) PYTHON=$(PYTHON) RUN_LIST="$$list" \
	      $(repro_taskset) bash experiments/pair.sh $$root $$p || exit 1; \
	  done; done

reproducibility: reproducibility-runs
	@$(MAKE) --no-print-directory repro-a-table repro-b-table
	@$(PYTHON) -m experiments.analysis.reproducibility --table-a $(repro-a_TABLE).csv --table-b $(repro-b_TABLE).csv \
	  --runs-a $(repro-a_RUNS_CSV) --runs-b $(repro-b_RUNS_CSV) --goal-pp $(REPRO_GOAL_PP) \
	  --taskset "$(REPRO_TASKSET)" --out $(REPRO_DIR)/reproducibility
