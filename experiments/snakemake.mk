# snakemake.mk: the study targets that run on the workflow engine
# (experiments/Snakefile; the studies: experiments/studies.yaml). Each target
# is one call of Snakemake with the study's name and the variables of make's
# command line (NAME=VALUE, as typed; knobs in the environment too), which
# experiments/studies.py applies over the study's own values and checks.
#
#   make reproduce-table SIZE=64x48 SEEDS=2      # renders what is missing, then the analysis
#   make reproduce-table SNAKEFLAGS=-n           # the engine's dry run: every job and why it would run
#   make -n reproduce-table                      # the same dry run, with the jobs' shell commands
#
# CORES: jobs at once (default: every core); timed renders (resource
# `timed`) run one at a time (TIMED_AT_ONCE), so that a study's timings are
# not taken beside its own next render; analysis jobs run beside them.

SNAKEMAKE ?= snakemake
CORES ?= $(shell nproc 2>/dev/null || echo 1)
TIMED_AT_ONCE ?= 1
SNAKEFLAGS ?=
# the knobs read from the environment too (as make's ?= defaults do)
SMK_ENV_KNOBS := SCENE SIZE SEEDS PHOTONS NNS METHODS ESTIMATES SUBPIXELS THREADS PM PM_ARGS TAG CONV_RUNROOT \
  REF REF_FAST RESULTS EE_TARGETS TIME BOOTSTRAP BOOTSTRAP_SEED PYTHON
SMK_OWN_VARS := SNAKEMAKE CORES TIMED_AT_ONCE SNAKEFLAGS
# yaml_quote TEXT: TEXT as a single-quoted YAML string (Snakemake's --config
# would otherwise read 1e5 as a number and "a: b" as a mapping)
yaml_quote = '$(subst ','',$(1))'
smk_given = $(foreach v,$(sort $(.VARIABLES)),$(if $(filter-out $(SMK_OWN_VARS),$(v)),$(if $(or \
  $(filter command line,$(origin $(v))),$(and $(filter environment,$(origin $(v))),$(filter $(SMK_ENV_KNOBS),$(v)))),$(v))))
smk_config = $(foreach v,$(smk_given),$(call shell_quote,$(v)=$(call yaml_quote,$(value $(v)))))
# make -n: the engine's dry run (the recipe line runs under -n: it is marked +)
smk_dry = $(if $(findstring n,$(firstword -$(MAKEFLAGS))),-n -p)
# smk STUDY,TARGET: the engine's command line making TARGET (a rule) of STUDY;
# its analysis rules (STUDY_*) run every time, as the tables' inputs may have
# changed beyond what file times tell (another REF, BOOTSTRAP, ...)
smk = $(SNAKEMAKE) -s experiments/Snakefile --cores $(CORES) --resources timed=$(TIMED_AT_ONCE) \
  --rerun-triggers mtime --rerun-incomplete --nolock $(or $(smk_dry),-q) $(SNAKEFLAGS) \
  --config STUDY=$(1) $(smk_config) $(if $(filter $(1),$(2)),--forcerun $(1)_collect) -- $(2)

.PHONY: reproduce-table
reproduce-table: $(BUILD)/photonmap | $(DEPS_TEST)
	+@$(call smk,table1,table1)
