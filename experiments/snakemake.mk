# snakemake.mk: the study targets that run on the workflow engine
# (experiments/Snakefile; the studies: experiments/studies.yaml). Each target
# is one call of Snakemake with the study's name and the variables of make's
# command line (NAME=VALUE, as typed; knobs in the environment too), which
# experiments/studies.py applies over the study's own values and checks.
#
#   make reproduce-table SIZE=64x48 SEEDS=2      # renders what is missing, then the analysis
#   make reproduce-table SNAKEFLAGS=-n           # the engine's dry run, quiet: the number of jobs per rule
#   make -n reproduce-table                      # the same dry run, with the jobs' shell commands
#   make reproduce-table CLUSTER=slurm           # every job on Slurm, the renders grouped
#
# CORES: jobs at once (default: every core); timed renders (resource
# `timed`) run one at a time (TIMED_AT_ONCE), so that a study's timings are
# not taken beside its own next render; analysis jobs run beside them.

SNAKEMAKE ?= snakemake
CORES ?= $(shell nproc 2>/dev/null || echo 1)
TIMED_AT_ONCE ?= 1
SNAKEFLAGS ?=
# the knobs read from the environment too (as make's ?= defaults do)
SMK_ENV_KNOBS := SCENE SIZE SEEDS TIME_REPEATS TIME_PROCESSES TIME_PROCESSES_MAX TIME_GAUGE TIME_CPU PHOTONS NNS METHODS ESTIMATES SUBPIXELS THREADS PM PM_ARGS TAG CONV_RUNROOT \
  REF REF_FAST RESULTS EE_TARGETS TIME BOOTSTRAP BOOTSTRAP_SEED PYTHON \
  CONV_REF_PHOTONS CONV_REF_FACTOR CONV_REF_NN CONV_REF_SEEDS CONV_REF_DIRECT RES_SIZES RES_TARGETS RES_REF \
  SCENES SCENES_CELL FIGURES REP_RULES BEYOND_SIZES BEYOND_TAUS BEYOND_GATE BEYOND_VARIANTS \
  REPRO_GOAL_PP REPRO_MAX_PP REPRO_BUSY_GOAL_PP REPRO_DRIFT FIG3_CELLS FIG3_PAPER_CELLS FIG_SEED FIG3_CROP FIG3_CROP_AT FIG_ERROR_BLOCK FIG_REF \
  FIG2_PHOTONS FIG2_NN FIG2_PLANE FIG2_WINDOW GLANCE_CELL EVAL_VARIANTS EVAL_GATHERS EVAL_CACHE EVAL_POV_SCENE OUT GATHERS GATHER_CORNELL_SIZES ONE_REPEAT_WORK
SMK_OWN_VARS := SNAKEMAKE CORES TIMED_AT_ONCE SNAKEFLAGS CLUSTER GROUP_RENDERS SLURM_JOBS SLURM_DIR SBATCH_OPTS SWEEP
# shell_quote TEXT: TEXT as one single-quoted shell word
shell_quote = '$(subst ','\'',$(1))'
# yaml_quote TEXT: TEXT as a single-quoted YAML string (Snakemake's --config
# would otherwise read 1e5 as a number and "a: b" as a mapping)
yaml_quote = '$(subst ','',$(1))'
smk_given = $(foreach v,$(sort $(.VARIABLES)),$(if $(filter-out $(SMK_OWN_VARS),$(v)),$(if $(or \
  $(filter command line,$(origin $(v))),$(and $(filter environment,$(origin $(v))),$(filter $(SMK_ENV_KNOBS),$(v)))),$(v))))
smk_config = $(foreach v,$(smk_given),$(call shell_quote,$(v)=$(call yaml_quote,$(value $(v)))))
# make -n: the engine's dry run (the recipe line runs under -n: it is marked +)
smk_dry = $(if $(findstring n,$(firstword -$(MAKEFLAGS))),-n -p)
# a dry run (make -n, or -n in SNAKEFLAGS): the Snakefile prints the wall
# time the cost model predicts for the missing renders (experiments/prediction.py)
smk_predict = $(if $(or $(smk_dry),$(filter -n --dry-run --dryrun -np -pn,$(SNAKEFLAGS))),PREDICT=1)
# CLUSTER=slurm: every job through Slurm instead of this machine: submitted
# with `sbatch --parsable` (SBATCH_OPTS: extra options, e.g. "--time=1:00:00
# --partition=short"; logs in SLURM_DIR/logs/JOBID.out), its state asked of
# squeue/scontrol (experiments/slurm/status.sh: no sacct, which a cluster
# without accounting cannot answer), scancel on an interrupt; the renders
# are sent GROUP_RENDERS jobs to one Slurm job (the group `renders`), at most
# SLURM_JOBS Slurm jobs at once. Every render then has a CPU of its own: no
# `timed` limit.
CLUSTER ?=
GROUP_RENDERS ?= 8
SLURM_JOBS ?= 100
SLURM_DIR ?= $(BUILD)/slurm
SBATCH_OPTS ?=
smk_slurm = --cluster $(call shell_quote,sbatch --parsable --output=$(abspath $(SLURM_DIR))/logs/%j.out $(SBATCH_OPTS)) \
  --cluster-status experiments/slurm/status.sh --cluster-cancel scancel --jobs $(SLURM_JOBS) \
  --group-components renders=$(GROUP_RENDERS) --latency-wait 30
smk_where = $(if $(filter slurm,$(CLUSTER)),$(smk_slurm),$(if $(strip $(CLUSTER)),$(error CLUSTER=$(CLUSTER): slurm, or empty for this machine),--cores $(CORES) --resources timed=$(TIMED_AT_ONCE)))
smk_logs = $(if $(and $(filter slurm,$(CLUSTER)),$(if $(smk_dry),,y)),mkdir -p $(SLURM_DIR)/logs && )

# smk STUDY,TARGET[,FIRST]: the engine's command line making TARGET (a rule)
# of STUDY; FIRST, the study's first analysis rule, and all after it run
# every time, as their inputs may have changed beyond what file times tell
# (another REF, BOOTSTRAP, ...)
smk = $(smk_logs)$(SNAKEMAKE) -s experiments/Snakefile $(smk_where) \
  --rerun-triggers mtime --rerun-incomplete --nolock $(or $(smk_dry),-q) $(SNAKEFLAGS) \
  --config STUDY=$(1) $(smk_predict) $(smk_config) $(if $(3),--forcerun $(3)) -- $(2)

# the study targets: STUDY (studies.yaml), its report rule, its first analysis rule
.PHONY: reproduce-table reproduce-runs list-runs caustic estimator-bias estimator-bias-runs figures sweep-slurm evaluate evaluate-references resolution resolution-runs scenes scenes-runs rep-study rep-study-runs beyond beyond-runs reproducibility reproducibility-runs reproducibility-runs gather gather-runs
reproduce-table: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,table1,table1,collect)
# Table 1's renders only; every render's record path, one per line
reproduce-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,table1,runs)
list-runs: | $(DEPS_TEST)
	@$(PYTHON) -m experiments.studies list-runs table1 $(smk_config)
caustic: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,caustic,caustic,collect)
estimator-bias: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,bias,bias,bias)
estimator-bias-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,bias,runs)
gather: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,gather,gather,collect)
gather-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,gather,runs)
resolution: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,resolution,resolution,collect)
resolution-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,resolution,runs)
scenes: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,scenes,scenes,collect)
scenes-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,scenes,runs)
rep-study: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,rep-study,rep_study,collect collect_rep)
rep-study-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,rep-study,runs)
beyond: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,beyond,beyond,collect collect_variant)
beyond-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,beyond,runs)
reproducibility: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,reproducibility,reproducibility,collect)
reproducibility-runs: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,reproducibility,runs)
figures: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,figures,figures)
# make evaluate SCENE=my.scene (rules/evaluate.smk); evaluate-references: its stages 1-3
evaluate: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,evaluate,evaluate,collect collect_variant collect_gather)
evaluate-references: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,evaluate,evaluate_references)

# `make sweep-slurm SWEEP=TARGET [knobs]`: the study target TARGET (one of
# SMK_TARGETS) with CLUSTER=slurm: Snakemake submits its renders to Slurm
SMK_TARGETS := reproduce-table reproduce-runs caustic estimator-bias estimator-bias-runs figures resolution \
  resolution-runs scenes scenes-runs rep-study rep-study-runs beyond beyond-runs reproducibility reproducibility-runs evaluate evaluate-references
sweep-slurm:
	$(if $(strip $(SWEEP)),,$(error sweep-slurm: give SWEEP=TARGET, a study target ($(SMK_TARGETS))))
	$(if $(filter-out $(SMK_TARGETS),$(SWEEP))$(word 2,$(SWEEP)),$(error sweep-slurm: SWEEP=$(SWEEP): not one study target ($(SMK_TARGETS))))
	+@$(MAKE) --no-print-directory $(SWEEP) CLUSTER=slurm
