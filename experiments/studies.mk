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

# ---- rep-study: each rule of REP_RULES a variant of Table 1 (precomputed,
# paper estimate), compared with Table 1's conventional renders
# a rule's render options: everyK, countN, shared
rep_args = $(strip $(if $(filter every%,$1),--rep-every $(patsubst every%,%,$1),$(if $(filter count%,$1),--rep-count \
  $(patsubst count%,%,$1),$(if $(filter shared,$1),--rep-tree shared,$(error rep-study: rule '$1' is not everyK, countN or shared)))))
define rep_study
rep-$(1)_SCENE = $$(SCENE)
rep-$(1)_SIZE = $$(SIZE)
rep-$(1)_SEEDS = $$(call knob,SEEDS,$$(rep_seeds))
rep-$(1)_PHOTONS = $$(PHOTONS)
rep-$(1)_NNS = $$(NNS)
rep-$(1)_METHODS = precomputed
rep-$(1)_ESTIMATES = paper
rep-$(1)_PM_ARGS = $$(call rep_args,$(1))
rep-$(1)_TAG = rep-$(1)
rep-$(1)_CONV = $$(table1_RUNROOT)
rep-$(1)_CONV_DEPS = $$(table1_RUN_FILES)
rep-$(1)_REF = $$(table1_REF)
rep-$(1)_REF_FAST = $$(table1_REF_FAST)
rep-$(1)_NO_REF = $$(table1_NO_REF)
rep-$(1)_RUNS_CSV = $$(REP_DIR)/runs-rep-$(1).csv
rep-$(1)_CELLS_CSV = $$(REP_DIR)/cells-rep-$(1).csv
rep-$(1)_TABLE = $$(REP_DIR)/table1-rep-$(1)
rep-$(1)_EQUAL_ERROR = $$(REP_DIR)/equal-error-rep-$(1)
$$(eval $$(call study,rep-$(1)))
endef
$(foreach r,$(REP_RULES),$(eval $(call rep_study,$(r))))
.PHONY: rep-study-runs
rep-study-runs: $(table1_RUN_FILES) $(foreach r,$(REP_RULES),$(rep-$(r)_RUN_FILES))
rep-study: table1-table $(REP_RULES:%=rep-%-table)
	$(if $(strip $(TAG)),$(error rep-study makes its own variants: leave TAG unset))
	@$(PYTHON) -m experiments.analysis.repstudy --base-runs $(RUNS_CSV) \
	  $(foreach r,$(REP_RULES),--variant $(r)=$(rep-$(r)_RUNS_CSV)) --paper experiments/paper-table1.csv \
	  --time $(TIME) --out $(REP_STUDY) --figure $(FIGURES)/rep-study.png --bootstrap $(BOOTSTRAP) \
	  --bootstrap-seed $(BOOTSTRAP_SEED)

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
conv_ref_grid_seeds = $(sort $(call seeds,$(SEEDS)) $(call seeds,$(rep_seeds)) $(call seeds,$(scenes_seeds)) $(EVAL_GRID_SEEDS))
define converged_ref_rule
$(dir $(call converged_ref,$(1),WxH))%.exr: $(1) | $$(BUILD)/photonmap $$(DEPS_TEST)
	@echo "reference: $(1) at $$*, conventional, corrected, --direct $$(CONV_REF_DIRECT), P_e=$$(CONV_REF_P) n=$$(CONV_REF_NN), seeds $$(CONV_REF_SEEDS), all cores"
	@$$(PYTHON) -m experiments.analysis.reference build --pm $$(PM) --scene $(1) --width $$(call size_w,$$*) \
	  --height $$(call size_h,$$*) --subpixels $$(SUBPIXELS) --photons $$(CONV_REF_P) --nn $$(CONV_REF_NN) \
	  --direct $$(CONV_REF_DIRECT) --seeds "$$(CONV_REF_SEEDS)" --grid-seeds "$$(conv_ref_grid_seeds)" \
	  --dir $$(dir $$@)$$* --out $$@
endef
$(foreach s,$(sort $(SCENE) $(SCENES)),$(eval $(call converged_ref_rule,$(s))))

# ---- resolution: the grid at every size of RES_SIZES (or SIZE), cheapest settings per target
res_sizes = $(if $(filter command line,$(origin RES_SIZES)),$(RES_SIZES),$(call knob,SIZE,$(RES_SIZES)))
res_seeds = $(call knob,SEEDS,$(SEEDS))
# res_ref WxH: the reference of one size (RES_REF=pov: the POV-Ray one where there is one)
res_pov = $(if $(filter pov,$(RES_REF)),$(shell bash experiments/findref.sh $(1) $(SCENE)))
res_ref = $(or $(call res_pov,$(1)),$(call converged_ref,$(SCENE),$(1)))
res_ref_desc = $(if $(call res_pov,$(1)),POV-Ray `$(call res_pov,$(1))`,ours: corrected$(comma) --direct $(CONV_REF_DIRECT)$(comma) P_e=$(CONV_REF_P)$(comma) n=$(CONV_REF_NN)$(comma) mean of seeds $(CONV_REF_SEEDS) (no grid render uses them)$(comma) same scene and settings$(comma) `$(call res_ref,$(1))` ($(if $(filter pov,$(RES_REF)),no POV-Ray reference of this size in reference/,RES_REF=ours: one kind of reference at every size)))
comma := ,
define res_study
res-$(1)_SCENE = $$(SCENE)
res-$(1)_SIZE = $(1)
res-$(1)_SEEDS = $$(res_seeds)
res-$(1)_PHOTONS = $$(PHOTONS)
res-$(1)_NNS = $$(NNS)
res-$(1)_METHODS = $$(METHODS)
res-$(1)_ESTIMATES = $$(ESTIMATES)
res-$(1)_REF = $$(call res_ref,$(1))
res-$(1)_REF_FAST = $$(if $$(call res_pov,$(1)),$$(shell bash experiments/findref.sh --fast $(1) $$(SCENE)))
res-$(1)_REF_DEPS = $$(if $$(call res_pov,$(1)),,$$(call converged_ref,$$(SCENE),$(1)))
res-$(1)_RUNS_CSV = $$(RES_DIR)/runs-$(1).csv
res-$(1)_CELLS_CSV = $$(RES_DIR)/cells-$(1).csv
res-$(1)_TABLE = $$(RES_DIR)/table-$(1)
res-$(1)_EQUAL_ERROR = $$(RES_DIR)/equal-error-$(1)
$$(eval $$(call study,res-$(1)))
endef
$(foreach s,$(res_sizes),$(eval $(call res_study,$(s))))
.PHONY: resolution-runs
resolution-runs: $(foreach s,$(res_sizes),$(res-$(s)_RUN_FILES) $(res-$(s)_REF_DEPS))
resolution: $(res_sizes:%=res-%-table)
	@$(PYTHON) -m experiments.analysis.resolution $(foreach s,$(res_sizes),--size $(s) $(res-$(s)_TABLE).csv "$(call res_ref_desc,$(s))") \
	  $(foreach s,$(res_sizes),--ref-exr $(s) "$(res-$(s)_REF)" $(res-$(s)_EQUAL_ERROR).csv) \
	  --targets "$(RES_TARGETS)" --time $(TIME) \
	  --grid "P_e in {$(PHOTONS)} x n in {$(NNS)} x {$(METHODS)} x estimates {$(ESTIMATES)}, seeds 1..$(res_seeds), threads: $(or $(THREADS),all)" \
	  --out $(RES_DIR)/resolution.md

# ---- scenes: the grid on every scene of SCENES at SIZE, each against our converged render of it
scenes_size = $(call knob,SIZE,$(scenes_size_default))
scenes_seeds = $(call knob,SEEDS,$(scenes_seeds_default))
scene_id = $(basename $(notdir $(1)))
define scene_study
scene-$(2)_SCENE = $(1)
scene-$(2)_SIZE = $$(scenes_size)
scene-$(2)_SEEDS = $$(scenes_seeds)
scene-$(2)_PHOTONS = $$(PHOTONS)
scene-$(2)_NNS = $$(NNS)
scene-$(2)_METHODS = $$(METHODS)
scene-$(2)_ESTIMATES = $$(ESTIMATES)
scene-$(2)_REF = $$(call converged_ref,$(1),$$(scenes_size))
scene-$(2)_REF_DEPS = $$(scene-$(2)_REF)
scene-$(2)_RUNS_CSV = $$(SCENES_DIR)/runs-$(2).csv
scene-$(2)_CELLS_CSV = $$(SCENES_DIR)/cells-$(2).csv
scene-$(2)_TABLE = $$(SCENES_DIR)/table-$(2)
scene-$(2)_EQUAL_ERROR = $$(SCENES_DIR)/equal-error-$(2)
$$(eval $$(call study,scene-$(2)))
endef
$(foreach s,$(SCENES),$(eval $(call scene_study,$(s),$(call scene_id,$(s)))))
.PHONY: scenes-runs
scenes-runs: $(foreach s,$(SCENES),$(scene-$(call scene_id,$(s))_RUN_FILES) $(scene-$(call scene_id,$(s))_REF_DEPS))
scenes: $(foreach s,$(SCENES),scene-$(call scene_id,$(s))-table)
	@$(PYTHON) -m experiments.analysis.scenes $(foreach s,$(SCENES),--scene $(s) $(scene-$(call scene_id,$(s))_TABLE).csv \
	  $(scene-$(call scene_id,$(s))_RUNS_CSV) $(scene-$(call scene_id,$(s))_EQUAL_ERROR).csv $(scene-$(call scene_id,$(s))_REF)) \
	  --cell "$(SCENES_CELL)" --size "$(scenes_size)" --ref-photons "$(CONV_REF_P)" --ref-nn "$(CONV_REF_NN)" \
	  --ref-seed "$(CONV_REF_SEEDS)" \
	  --grid "P_e in {$(PHOTONS)} x n in {$(NNS)} x {$(METHODS)} x estimates {$(ESTIMATES)}, seeds 1..$(scenes_seeds), threads: $(or $(THREADS),all)" \
	  --figures "$(FIGURES)" --out "$(SCENES_DIR)/scenes"

# ---- refusals before any render: a study whose reference is missing
ifneq ($(call goal,rep-study),)
ifeq ($(strip $(table1_REF)),)
$(error rep-study: no reference: $(table1_NO_REF))
endif
endif
ifneq ($(call goal,resolution),)
ifneq ($(filter command line,$(origin REF) $(origin REF_FAST)),)
$(error resolution: its reference per size is RES_REF=ours (our converged render) or RES_REF=pov (POV-Ray where reference/ has one), not REF=)
endif
endif
ifneq ($(call goal,scenes),)
ifneq ($(filter command line,$(origin SCENE) $(origin REF)),)
$(error scenes: runs every scene of SCENES against its own converged reference: give SCENES="a.scene b.scene", not SCENE= or REF=)
endif
endif
