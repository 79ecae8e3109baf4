# studies.mk: every study, declared once for the mechanism of
# experiments/study.mk (one make target per render, one analysis call), and
# the study targets a user runs. Knobs and defaults: experiments/config.mk.
# Each study writes its files under RESULTS/<study>/ (results/README.md).
#
#   make reproduce-table [SIZE=256x192 SEEDS=3 PHOTONS="50000 500000" NNS="10 100" RESULTS=/tmp/quick]
#   make -j2 reproduce-runs      # only the renders, two at a time
#   make rep-study | resolution | scenes   (same knobs: SIZE, SEEDS, ...)
# (reproduce-table, caustic and estimator-bias: experiments/studies.yaml, on Snakemake)

# ---- Table 1: the paper's grid on SCENE at SIZE (a variant: TAG, PM_ARGS, CONV_RUNROOT)
table1_SCENE = $(SCENE)
table1_SIZE = $(SIZE)
table1_SEEDS = $(SEEDS)
table1_PHOTONS = $(PHOTONS)
table1_NNS = $(NNS)
table1_METHODS = $(METHODS)
table1_ESTIMATES = $(ESTIMATES)
table1_PM_ARGS = $(PM_ARGS)
table1_TAG = $(TAG)
table1_CONV = $(CONV_RUNROOT)
table1_REF = $(REF_FILE)
table1_REF_FAST = $(REF_FAST_FILE)
table1_NO_REF = none of $(SCENE) at $(SIZE) in reference/$(SCENE_NAME)/: give REF=FILE.exr (a converged render of the scene at $(SIZE)), or run `make scenes SCENES=$(SCENE) SIZE=$(SIZE)`, which renders its own converged reference
table1_RUNS_CSV = $(RUNS_CSV)
table1_CELLS_CSV = $(CELLS_CSV)
table1_TABLE = $(TABLE)
table1_EQUAL_ERROR = $(EQUAL_ERROR)
$(eval $(call study,table1))
# the names the other files use
RUNROOT := $(table1_RUNROOT)
RUN_FILES := $(table1_RUN_FILES)

list-runs:
	@printf '%s\n' $(RUN_FILES)
reproduce-runs: $(table1_RUN_FILES)

# ---- our converged reference of a scene at a size (resolution, scenes,
# evaluate): method-neutral, its own error measured
# (experiments/analysis/reference.py): the corrected estimate with shadow-ray
# direct light at CONV_REF_P photons (CONV_REF_PHOTONS, or CONV_REF_FACTOR x
# the grid's largest P_e), n = CONV_REF_NN, the mean of the seeds
# CONV_REF_SEEDS (none a grid seed), each also at half the photons (its
# kernel bias); WxH.json beside WxH.exr holds noise, bias and the settings
# converged_ref SCENE,WxH: the file
CONV_REF_P = $(or $(strip $(CONV_REF_PHOTONS)),$(shell echo $(PHOTONS) | tr ' ' '\n' | sort -n | tail -n 1 | awk -v f=$(CONV_REF_FACTOR) '{ print $$1 * f }'))
conv_ref_tag = p$(CONV_REF_P)-n$(CONV_REF_NN)-$(CONV_REF_DIRECT)-s$(SUBPIXELS)-seeds$(subst $(space),_,$(strip $(CONV_REF_SEEDS)))
space := $(subst ,, )
converged_ref = $(RESULTS)/runs/$(basename $(notdir $(1)))-convref-$(conv_ref_tag)/$(2).exr
# the seeds every grid may use (the reference must share none of them)
scenes_seeds = $(call knob,SEEDS,$(scenes_seeds_default))
conv_ref_grid_seeds = $(sort $(call seeds,$(SEEDS)) $(call seeds,$(rep_seeds)) $(call seeds,$(scenes_seeds)) $(EVAL_GRID_SEEDS))
scene_id = $(basename $(notdir $(1)))
define converged_ref_rule
$(dir $(call converged_ref,$(1),WxH))%.exr: $(1) | $$(BUILD)/photonmap $$(DEPS_TEST)
	@echo "reference: $(1) at $$*, conventional, corrected, --direct $$(CONV_REF_DIRECT), P_e=$$(CONV_REF_P) n=$$(CONV_REF_NN), seeds $$(CONV_REF_SEEDS), all cores"
	@$$(PYTHON) -m experiments.analysis.reference build --pm $$(PM) --scene $(1) --width $$(call size_w,$$*) \
	  --height $$(call size_h,$$*) --subpixels $$(SUBPIXELS) --photons $$(CONV_REF_P) --nn $$(CONV_REF_NN) \
	  --direct $$(CONV_REF_DIRECT) --seeds "$$(CONV_REF_SEEDS)" --grid-seeds "$$(conv_ref_grid_seeds)" \
	  --dir $$(dir $$@)$$* --out $$@
endef
$(eval $(call converged_ref_rule,$(SCENE)))
