# study.mk: the one mechanism behind every study target (reproduce-table,
# rep-study, caustic, resolution, scenes, estimator-bias). A study is
# declared once, as variables ID_* (experiments/studies.mk), and
#
#   $(eval $(call study,ID))
#
# expands it into one make target per render and one analysis call:
#
#   ID_SCENE ID_SIZE (WxH) ID_SEEDS (count: seeds 1..N) ID_PHOTONS ID_NNS
#   ID_METHODS ID_ESTIMATES   the grid: every P_e x n x method x estimate x seed
#   ID_SUBPIXELS ID_PM_ARGS ID_TAG   render settings; TAG names a variant's run root
#   ID_REF ID_REF_FAST        the reference EXR of the error columns (and its floor)
#   ID_REF_DEPS               files make builds before the analysis (a reference we render)
#   ID_CONV ID_CONV_DEPS      the run root of the conventional renders compared
#                             with (default: the study's own) and their targets
#   ID_RUNS_CSV ID_CELLS_CSV ID_TABLE ID_EQUAL_ERROR   the analysis files (TABLE,
#                             EQUAL_ERROR: stems of .md and .csv)
#
# which defines
#   ID_RUNROOT ID_RUN_NAMES ID_RUN_FILES   the run layout of the study
#   ID-runs    phony: every render (one make target each: make -j, resuming,
#              `make sweep-slurm SWEEP=ID-runs`); with both methods in
#              ID_METHODS the two renders of one (cell, seed) are one recipe
#              (experiments/pair.sh: back to back, the order alternating with
#              the seed), and the sweep's task list has one task per pair
#   ID-table   phony: the renders, then experiments/analysis collect -> RUNS_CSV
#              and CELLS_CSV, table -> TABLE.{md,csv}, equal_error -> EQUAL_ERROR.{md,csv}
#
# The run layout (experiments/README.md, "The run layout") is written here
# once: run_root, run_cells and run_names; experiments/run.sh makes one
# render's files and experiments/analysis/runs.py reads them.

# run_root SCENE,WxH,SUBPIXELS,TAG: where a study's renders live
run_root = $(RESULTS)/runs/$(basename $(notdir $(1)))-$(2)-s$(3)-$(T_LABEL)$(if $(strip $(4)),-$(strip $(4)))
# run_cells PHOTONS,NNS,METHODS,ESTIMATES: the cell directories, METHOD-ESTIMATE-pP-nN
run_cells = $(foreach p,$(1),$(foreach n,$(2),$(foreach m,$(3),$(foreach e,$(4),$(m)-$(e)-p$(p)-n$(n)))))
# run_names CELLS,SEEDS: CELL/seedK, seeds outermost (a partial run has every
# cell at the first seeds, and slow phases of a shared machine spread over all cells)
run_names = $(foreach s,$(2),$(foreach c,$(1),$(c)/seed$(s)))
# seeds N: 1..N (N checked: a positive integer)
seeds = $(if $(filter-out 0,$(shell echo '$(strip $(1))' | grep -xE '[0-9]+')),$(shell seq 1 $(1)),$(error SEEDS=$(1): a positive number of seeds))
# size_w / size_h WxH: the width and height (checked: W x H, both positive
# and at most the renderer's largest side, 16384)
size_ok = $(if $(shell echo '$(strip $(1))' | grep -xE '[1-9][0-9]*x[1-9][0-9]*'),$(if $(shell echo '$(strip $(1))' | awk -Fx '$$1 <= 16384 && $$2 <= 16384'),$(1),$(error SIZE=$(1): each side must be at most 16384, the renderer's --width and --height range)),$(error SIZE=$(1): not WxH (e.g. 512x384)))
size_w = $(word 1,$(subst x, ,$(call size_ok,$(1))))
size_h = $(word 2,$(subst x, ,$(call size_ok,$(1))))

define study
$(1)_SUBPIXELS ?= $$(SUBPIXELS)
# expanded once, here (the checks and seq run once per study, not per render)
$(1)_W := $$(call size_w,$$($(1)_SIZE))
$(1)_H := $$(call size_h,$$($(1)_SIZE))
$(1)_RUNROOT := $$(or $$($(1)_RUNROOT),$$(call run_root,$$($(1)_SCENE),$$($(1)_SIZE),$$($(1)_SUBPIXELS),$$($(1)_TAG)))
$(1)_CONV := $$(or $$($(1)_CONV),$$($(1)_RUNROOT))
$(1)_SEED_LIST := $$(call seeds,$$($(1)_SEEDS))
$(1)_RUN_NAMES := $$(call run_names,$$(call run_cells,$$($(1)_PHOTONS),$$($(1)_NNS),$$($(1)_METHODS),$$($(1)_ESTIMATES)),$$($(1)_SEED_LIST))
$(1)_RUN_FILES := $$($(1)_RUN_NAMES:%=$$($(1)_RUNROOT)/%.run.json)
$(1)_REF := $$($(1)_REF)

$(1)_RUN_ENV = PM=$$(PM) PM_ARGS="$$($(1)_PM_ARGS)" SCENE=$$($(1)_SCENE) WIDTH=$$($(1)_W) \
	  HEIGHT=$$($(1)_H) SUBPIXELS=$$($(1)_SUBPIXELS) THREADS_ARG=$$(T_ARG) PYTHON=$$(PYTHON) \
	  RUN_LIST="$$($(1)_RUN_NAMES)"
# one render (experiments/run.sh writes its files, the record last)
$$($(1)_RUNROOT)/%.run.json: | $$(BUILD)/photonmap $$(DEPS_TEST)
	@$$($(1)_RUN_ENV) bash experiments/run.sh $$($(1)_RUNROOT) $$*
ifeq ($$(sort $$(filter conventional precomputed,$$($(1)_METHODS))),conventional precomputed)
# both methods: the two renders of one (cell, seed) are one recipe, back to
# back in an order alternating with the seed (experiments/pair.sh): a
# pattern rule with two targets makes both at once, so make -j runs it once,
# and a missing record of either renders the pair again
$$($(1)_RUNROOT)/conventional-%.run.json $$($(1)_RUNROOT)/precomputed-%.run.json: | $$(BUILD)/photonmap $$(DEPS_TEST)
	@$$($(1)_RUN_ENV) bash experiments/pair.sh $$($(1)_RUNROOT) $$*
endif

.PHONY: $(1)-runs $(1)-table
$(1)-runs: $$($(1)_RUN_FILES)
$(1)-table: $$($(1)_RUN_FILES) $$($(1)_CONV_DEPS) $$($(1)_REF_DEPS)
	$$(if $$($(1)_REF),,$$(error $(1): no reference: $$($(1)_NO_REF)))
	@mkdir -p $$(dir $$($(1)_RUNS_CSV) $$($(1)_CELLS_CSV) $$($(1)_TABLE) $$($(1)_EQUAL_ERROR))
	@$$(PYTHON) -m experiments.analysis.collect --runroot $$($(1)_RUNROOT) --conv-runroot $$($(1)_CONV) \
	  --scene $$($(1)_SCENE) --width $$($(1)_W) --height $$($(1)_H) \
	  --subpixels $$($(1)_SUBPIXELS) --threads "$$(T_ARG)" --tag "$$($(1)_TAG)" --methods "$$($(1)_METHODS)" \
	  --estimates "$$($(1)_ESTIMATES)" --photons "$$($(1)_PHOTONS)" --nns "$$($(1)_NNS)" --seeds "$$($(1)_SEED_LIST)" \
	  --ref "$$($(1)_REF)" --ref-fast "$$($(1)_REF_FAST)" --runs-csv $$($(1)_RUNS_CSV) --cells-csv $$($(1)_CELLS_CSV)
	@$$(PYTHON) -m experiments.analysis.table --runs-csv $$($(1)_RUNS_CSV) --cells-csv $$($(1)_CELLS_CSV) \
	  --paper experiments/paper-table1.csv --out $$($(1)_TABLE) --equal-error $$($(1)_EQUAL_ERROR).md \
	  --pm $$(PM) --pm-args "$$($(1)_PM_ARGS)" --runroot $$($(1)_RUNROOT) --bootstrap $$(BOOTSTRAP) --bootstrap-seed $$(BOOTSTRAP_SEED)
	@$$(PYTHON) -m experiments.analysis.equal_error --runs-csv $$($(1)_RUNS_CSV) --out $$($(1)_EQUAL_ERROR) \
	  --targets "$$(EE_TARGETS)" --time $$(TIME) --bootstrap $$(BOOTSTRAP) --bootstrap-seed $$(BOOTSTRAP_SEED) --pm $$(PM)
endef

# knob NAME,DEFAULT: the value of a knob every study reads (SIZE, SEEDS,
# SCENE, PHOTONS, NNS, ...) when it was given on the command line, else the
# study's own DEFAULT
knob = $(if $(filter command line,$(origin $(1))),$($(1)),$(2))
# goal NAMES: non-empty when one of the targets NAMES was asked for
goal = $(filter $(1),$(MAKECMDGOALS))
