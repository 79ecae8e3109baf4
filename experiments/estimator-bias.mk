# `make estimator-bias`: the estimators' bias in the analytic scene
# (scenes/furnace.scene, radiance exactly 1 everywhere). For every method,
# estimate (paper, corrected), n in BIAS_NNS and seed in 1..BIAS_SEEDS, one
# render (one make target, so `make -j` and a Slurm array can run them):
# $(BIAS_DIR)/<method>-<estimate>-n<n>/seed<k>.json (the stats JSON holds
# the image's mean radiance). experiments/estimator_bias.py turns them into
# BIAS_OUT.md and .csv: mean radiance / exact with its 95% CI, beside the
# n/(n-1) law. Settings the renderer refuses (precomputed paper with n = 2)
# leave {"refused": true} and the message in a .refused file beside it.
# Variables: experiments/config.mk.

BIAS_ESTIMATES := paper corrected
BIAS_RUNS := $(foreach m,conventional precomputed,$(foreach e,$(BIAS_ESTIMATES),$(foreach n,$(BIAS_NNS),\
  $(foreach s,$(shell seq 1 $(BIAS_SEEDS)),$(BIAS_DIR)/$(m)-$(e)-n$(n)/seed$(s).json))))

# one render: the target's directory names method, estimate and n
$(BIAS_DIR)/%.json: | $(BUILD)/photonmap
	@d=$(notdir $(patsubst %/,%,$(dir $@))); m=$${d%%-*}; rest=$${d#*-}; e=$${rest%%-*}; n=$${rest#*-n}; \
	s=$(notdir $*); s=$${s#seed}; mkdir -p $(dir $@); \
	bc=; [ "$$e" = corrected ] && bc=--bias-correction; \
	if $(PM) render $(BIAS_SCENE) --method $$m $$bc --nn $$n --seed $$s --photons $(BIAS_PHOTONS) \
	     --width $(word 1,$(subst x, ,$(BIAS_SIZE))) --height $(word 2,$(subst x, ,$(BIAS_SIZE))) --subpixels 1 \
	     --threads $(T_ARG) --stats $@.tmp --quiet 2> $@.err; then mv $@.tmp $@; rm -f $@.err; \
	else rc=$$?; rm -f $@.tmp; if [ $$rc -eq 2 ]; then mv $@.err $(@:.json=.refused); echo '{"refused": true}' > $@; \
	else cat $@.err >&2; exit $$rc; fi; fi

.PHONY: estimator-bias-runs
estimator-bias-runs: $(BIAS_RUNS)
estimator-bias: estimator-bias-runs
	$(PYTHON) experiments/estimator_bias.py --dir $(BIAS_DIR) --nns "$(BIAS_NNS)" --seeds $(BIAS_SEEDS) \
	  --photons $(BIAS_PHOTONS) --size $(BIAS_SIZE) --scene $(BIAS_SCENE) --out $(BIAS_OUT)
