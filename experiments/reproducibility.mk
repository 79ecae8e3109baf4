# reproducibility.mk: `make reproducibility`: the Table-1 grid of SCENE
# rendered twice, runs A and B, interleaved in time, and how far the two runs'
# paired results lie apart (experiments/analysis/reproducibility.py ->
# REPRO_DIR/reproducibility.{md,csv}). Knobs (experiments/config.mk): SIZE
# (default here 512x384), SEEDS (default here 10), PHOTONS, NNS, ESTIMATES, REF; REPRO_TASKSET:
# the CPU list every render is pinned to with taskset (default: the last CPU;
# empty: no pinning).
#
# Expected run time at the defaults on a quiet 2-core machine: about 25
# minutes (measured: 24 minutes for 10 seeds, 960 renders, the converged
# reference and both tables). Per seed the 24 cells x 2 methods at 512x384
# take about 45 s of the renderer's own time, about 55 s with start-up and
# image writing, so 2 runs x 10 seeds about 19 minutes; the converged
# reference (8 renders at 10M and 5M photons, all cores, after the timed
# renders) about 3 minutes; the two tables' bootstraps 1-2 minutes.
#
# Reference: the POV-Ray one of SCENE at SIZE where reference/ has one
# (experiments/findref.sh), otherwise, as `make resolution` and `make scenes`
# do, the method-neutral converged reference (studies.mk's converged_ref,
# CONV_REF_* knobs), rendered after the timed renders so that it does not
# load the machine while they run; reproducibility.md prints its measured
# error (noise and kernel bias). REF=FILE overrides both.
#
# Design (chosen for the goal, median |ratio A - ratio B| <= REPRO_GOAL_PP):
# - timer: the renderer's own time_s.total (table.py's paired ratio: no
#   start-up, no image writing), process CPU only a secondary column; the
#   photon-trace phase (identical code in both methods) is the drift control;
# - pairing: each (cell, seed) is a pair, conventional and precomputed back to
#   back (experiments/pair.sh, order alternating with the seed), the ratio a
#   per-seed paired log ratio, so a slow minute falls on both methods;
# - interleaving: the pairs are rendered in one sequence, pair k of run A
#   then pair k of run B, with A first at odd k and B first at even k, so
#   that a slow phase of the machine falls on both runs alike; the two runs
#   are otherwise two independent studies (their own run roots, collect and
#   table), exactly as `make reproduce-table` twice would be;
# - pinning: every render (single-threaded, THREADS=1) on one CPU, the same
#   for both runs, so that neither run migrates between cores or shares one
#   with make and the shell (REPRO_TASKSET= turns it off; with THREADS other
#   than 1 give a list of as many CPUs);
# - repeats: the seeds are the repeats (SEEDS, default REPRO_SEEDS_DEFAULT,
#   10): each ratio's interval is over seeds; more seeds narrow it at
#   proportional cost. At 5 seeds, with light work on the other core, the
#   median |delta| was 3.36 pp; at 10 seeds on the idle machine 2.89 pp
#   (results/reproducibility/reproducibility.md).
# A pair already rendered (both records present) is kept: the target resumes.

repro_size = $(call knob,SIZE,$(REPRO_SIZE_DEFAULT))
repro_seeds = $(call knob,SEEDS,$(REPRO_SEEDS_DEFAULT))
# the POV-Ray reference at that size (none: the converged reference, built by make)
repro_pov := $(if $(REF),,$(shell bash experiments/findref.sh $(repro_size) $(SCENE)))
repro_ref_deps = $(if $(or $(REF),$(repro_pov)),,$(call converged_ref,$(SCENE),$(repro_size)))
define repro_study
repro-$(1)_SCENE = $$(SCENE)
repro-$(1)_SIZE = $$(repro_size)
repro-$(1)_SEEDS = $$(repro_seeds)
repro-$(1)_PHOTONS = $$(PHOTONS)
repro-$(1)_NNS = $$(NNS)
repro-$(1)_METHODS = conventional precomputed
repro-$(1)_ESTIMATES = $$(ESTIMATES)
repro-$(1)_TAG = repro-$(1)
repro-$(1)_REF = $$(or $$(REF),$$(repro_pov),$$(call converged_ref,$$(SCENE),$$(repro_size)))
repro-$(1)_REF_FAST = $$(if $$(REF),$$(REF_FAST),$$(if $$(repro_pov),$$(shell bash experiments/findref.sh --fast $$(repro_size) $$(SCENE))))
repro-$(1)_REF_DEPS = $$(repro_ref_deps)
repro-$(1)_RUNS_CSV = $$(REPRO_DIR)/runs-$(1).csv
repro-$(1)_CELLS_CSV = $$(REPRO_DIR)/cells-$(1).csv
repro-$(1)_TABLE = $$(REPRO_DIR)/table1-$(1)
repro-$(1)_EQUAL_ERROR = $$(REPRO_DIR)/equal-error-$(1)
$$(eval $$(call study,repro-$(1)))
endef
$(foreach r,a b,$(eval $(call repro_study,$(r))))

# the pair names (ESTIMATE-pP-nN/seedK) in the grid's order, seeds outermost
repro_pairs = $(call run_names,$(call run_cells,$(PHOTONS),$(NNS),x,$(ESTIMATES)),$(call seeds,$(repro_seeds)))
repro_taskset = $(if $(strip $(REPRO_TASKSET)),taskset -c $(strip $(REPRO_TASKSET)))

.PHONY: reproducibility reproducibility-runs
reproducibility-runs: | $(BUILD)/photonmap $(DEPS_TEST)
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
	  --taskset "$(REPRO_TASKSET)" --ref "$(repro-a_REF)" --equal-error-a $(repro-a_EQUAL_ERROR).csv \
	  --out $(REPRO_DIR)/reproducibility
