# `make sweep-slurm`: a list of make targets as a Slurm job array, one array
# task per target, each running `make VARS TARGET` in this repository with
# the variables given to `make sweep-slurm` (experiments/README.md):
#
#   make sweep-slurm TASKS=targets.txt [SLURM_DIR=build/slurm] [SBATCH_OPTS="--time=1:00:00 ..."]
#   make sweep-slurm SWEEP=reproduce-runs SIZE=256x192 SEEDS=3   # the target's prerequisites
#   sbatch build/slurm/sweep.sbatch
#
# The work is in experiments/slurm.sh; this file only hands it the make
# variables of the command line (NAME=VALUE, one per line, as typed, written
# by the recipe's shell, so that `make -n sweep-slurm` writes nothing), so
# that every task expands its target exactly as this make would. Variables:
# experiments/config.mk (TASKS, SWEEP, SLURM_DIR, SBATCH_OPTS).

# the variables of this command line, less sweep-slurm's own
SLURM_OWN_VARS := TASKS SWEEP SLURM_DIR SBATCH_OPTS
SLURM_PASS_VARS = $(foreach v,$(sort $(.VARIABLES)),$(if $(filter command line,$(origin $(v))),$(if $(filter $(SLURM_OWN_VARS),$(v)),,$(v))))

.PHONY: sweep-slurm sweep-slurm-nothing
# an empty goal for reading make's database (`make -pq sweep-slurm-nothing`)
sweep-slurm-nothing:

$(SLURM_DIR):
	@mkdir -p $@

# the make a task runs (not written as $(MAKE) in the recipe: make would run
# that line under -n)
SLURM_MAKE = $(MAKE)
# shell_quote TEXT: TEXT as one single-quoted shell word
shell_quote = '$(subst ','\'',$(1))'
sweep-slurm: all | $(SLURM_DIR)
	@$(if $(strip $(SLURM_PASS_VARS)),printf '%s\n' $(foreach v,$(SLURM_PASS_VARS),$(call shell_quote,$(v)=$(value $(v)))),:) > $(SLURM_DIR)/make-vars.tmp
	@mv $(SLURM_DIR)/make-vars.tmp $(SLURM_DIR)/make-vars
	@SLURM_DIR=$(SLURM_DIR) REPO=$(CURDIR) MAKE_CMD="$(SLURM_MAKE)" TASKS="$(TASKS)" SWEEP="$(SWEEP)" \
	  SBATCH_OPTS="$(SBATCH_OPTS)" bash experiments/slurm.sh
