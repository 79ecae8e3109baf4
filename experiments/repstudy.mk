# repstudy.mk: the rule of `make rep-study`: which rule for choosing
# representatives reproduces the paper's cost pattern. It brings the
# untagged grid up to date (`make reproduce-table`: the default rule and the
# conventional renders), renders every rule of REP_RULES as a variant of the
# grid (TAG=rep-RULE, precomputed only, paper estimate, REP_SEEDS seeds,
# compared with the untagged grid's conventional renders; each its own
# table1-rep-RULE.*), then experiments/analysis/repstudy.py fits the cost
# model per rule and P_e and writes REP_STUDY.{md,csv}, REP_STUDY-cells.csv
# and FIGURES/rep-study.png. Variables: experiments/config.mk.

# a rule's render options: everyK, countN, shared
rep_args = $(strip $(if $(filter every%,$1),--rep-every $(patsubst every%,%,$1),$(if $(filter count%,$1),--rep-count \
  $(patsubst count%,%,$1),$(if $(filter shared,$1),--rep-tree shared,$(error rep-study: rule '$1' is not everyK, countN or shared)))))

rep-study:
	$(if $(strip $(TAG)),$(error rep-study makes its own variants: leave TAG unset))
	@$(MAKE) --no-print-directory reproduce-table
	@$(foreach r,$(REP_RULES),$(MAKE) --no-print-directory reproduce-table TAG=rep-$(r) PM_ARGS="$(call rep_args,$(r))" \
	  METHODS=precomputed ESTIMATES=paper SEEDS=$(REP_SEEDS) SEED_LIST="$(wordlist 1,$(REP_SEEDS),$(SEED_LIST))" \
	  CONV_RUNROOT=$(RUNROOT) &&) true
	@$(PYTHON) -m experiments.analysis.repstudy --base-runs $(RUNS_CSV) \
	  $(foreach r,$(REP_RULES),--variant $(r)=$(RESULTS)/runs-rep-$(r).csv) --paper experiments/paper-table1.csv \
	  --time $(EE_TIME) --out $(REP_STUDY) --figure $(FIGURES)/rep-study.png --bootstrap $(BOOTSTRAP) \
	  --bootstrap-seed $(BOOTSTRAP_SEED)
