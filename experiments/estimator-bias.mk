# `make estimator-bias`: the estimators' bias in the analytic scene
# (scenes/furnace.scene, radiance exactly 1 everywhere). Every method,
# estimate (paper, corrected), n in BIAS_NNS and seed in 1..BIAS_SEEDS is one
# render, one make target, made by experiments/run.sh exactly like the
# grid's (so `make -j` and a Slurm array run them, and a refused setting,
# precomputed paper with n = 2, is recorded as not applicable):
# BIAS_DIR/<method>-<estimate>-p<BIAS_PHOTONS>-n<n>/seed<k>.run.json.
# experiments/analysis/estimator_bias.py turns the stats JSONs (the image's
# mean radiance) into BIAS_OUT.md and .csv. Variables: experiments/config.mk.

BIAS_CELLS = $(foreach m,conventional precomputed,$(foreach e,paper corrected,$(foreach n,$(BIAS_NNS),$(m)-$(e)-p$(BIAS_PHOTONS)-n$(n))))
BIAS_RUN_NAMES = $(foreach s,$(shell seq 1 $(BIAS_SEEDS)),$(foreach c,$(BIAS_CELLS),$(c)/seed$(s)))
BIAS_RUNS = $(BIAS_RUN_NAMES:%=$(BIAS_DIR)/%.run.json)

$(BIAS_DIR)/%.run.json: | $(BUILD)/photonmap
	@PM=$(PM) SCENE=$(BIAS_SCENE) WIDTH=$(word 1,$(subst x, ,$(BIAS_SIZE))) HEIGHT=$(word 2,$(subst x, ,$(BIAS_SIZE))) \
	  SUBPIXELS=1 THREADS_ARG=$(T_ARG) PYTHON=$(PYTHON) RUN_LIST="$(BIAS_RUN_NAMES)" bash experiments/run.sh $(BIAS_DIR) $*

.PHONY: estimator-bias-runs
estimator-bias-runs: $(BIAS_RUNS)
estimator-bias: estimator-bias-runs
	$(PYTHON) -m experiments.analysis.estimator_bias --dir $(BIAS_DIR) --nns "$(BIAS_NNS)" --seeds $(BIAS_SEEDS) \
	  --photons $(BIAS_PHOTONS) --size $(BIAS_SIZE) --scene $(BIAS_SCENE) --out $(BIAS_OUT)
