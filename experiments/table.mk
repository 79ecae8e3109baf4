# table.mk: the rules of `make reproduce-table` (and `make reproduce-runs`,
# `make list-runs`): the paper's Table 1 grid rendered with several seeds,
# then the analysis layer (experiments/analysis/, Debian's python3).
#
#   make reproduce-table                      # 1024x768, 2x2 samples, 5 seeds, 1 thread, both estimates
#   make reproduce-table SIZE=256x192 SEEDS=3 PHOTONS="50000 500000" NNS="10 100" RESULTS=/tmp/quick
#   make -j2 reproduce-runs                   # only the renders, two at a time (then reproduce-table)
#
# One make target per render:
#   RUNROOT/<method>-<estimate>-p<P_e>-n<n>/seed<k>.run.json
# (RUNROOT = RESULTS/runs/<scene>-<W>x<H>-s<S>-t<T>[-TAG]), written by
# experiments/run.sh after the render's seed<k>.exr and seed<k>.stats.json,
# so an interrupted run resumes with the renders that are missing, and
# `make list-runs` names every target (one per line) for a job array.
# Then experiments/analysis/collect.py writes RUNS_CSV (one row per render)
# and CELLS_CSV (one row per cell: bias and variance over seeds),
# table.py writes TABLE.csv and TABLE.md, equal_error.py EQUAL_ERROR.md/.csv.
# Variables: experiments/config.mk.

CELL_NAMES = $(foreach p,$(PHOTONS),$(foreach n,$(NNS),$(foreach m,$(METHODS),$(foreach e,$(ESTIMATES),$(m)-$(e)-p$(p)-n$(n)))))
# seeds outermost: a partial run has every cell at the first seeds, and slow
# phases of a shared machine spread over all cells
RUN_NAMES = $(foreach s,$(SEED_LIST),$(foreach c,$(CELL_NAMES),$(c)/seed$(s)))
RUN_FILES = $(RUN_NAMES:%=$(RUNROOT)/%.run.json)

# One render.
$(RUNROOT)/%.run.json: | $(BUILD)/photonmap
	@PM=$(PM) PM_ARGS="$(PM_ARGS)" SCENE=$(SCENE) WIDTH=$(WIDTH) HEIGHT=$(HEIGHT) SUBPIXELS=$(SUBPIXELS) \
	  THREADS_ARG=$(T_ARG) PYTHON=$(PYTHON) RUN_LIST="$(RUN_NAMES)" bash experiments/run.sh $(RUNROOT) $*

list-runs:
	@printf '%s\n' $(RUN_FILES)
reproduce-runs: $(RUN_FILES)
reproduce-table: $(RUN_FILES)
	@$(PYTHON) -m experiments.analysis.collect --runroot $(RUNROOT) --conv-runroot $(CONV_RUNROOT) \
	  --scene $(SCENE) --width $(WIDTH) --height $(HEIGHT) --subpixels $(SUBPIXELS) --threads "$(T_ARG)" --tag "$(TAG)" \
	  --methods "$(METHODS)" --estimates "$(ESTIMATES)" --photons "$(PHOTONS)" --nns "$(NNS)" --seeds "$(SEED_LIST)" \
	  --ref "$(REF_FILE)" --ref-fast "$(REF_FAST_FILE)" --runs-csv $(RUNS_CSV) --cells-csv $(CELLS_CSV)
	@$(PYTHON) -m experiments.analysis.table --runs-csv $(RUNS_CSV) --cells-csv $(CELLS_CSV) \
	  --paper experiments/paper-table1.csv --out $(TABLE) --equal-error $(EQUAL_ERROR).md \
	  --pm $(PM) --pm-args "$(PM_ARGS)" --runroot $(RUNROOT) --bootstrap $(BOOTSTRAP) --bootstrap-seed $(BOOTSTRAP_SEED)
	@$(PYTHON) -m experiments.analysis.equal_error --runs-csv $(RUNS_CSV) --out $(EQUAL_ERROR) \
	  --targets "$(EE_TARGETS)" --time $(EE_TIME) --bootstrap $(BOOTSTRAP) --bootstrap-seed $(BOOTSTRAP_SEED) --pm $(PM)
