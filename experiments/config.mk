# config.mk: every variable the experiment targets share, in one place
# (included by the top Makefile before experiments/*.mk). Each can be set on
# the command line, e.g. `make reproduce-table SIZE=256x192 REPEATS=1`.

RESULTS ?= results
SCENE ?= scenes/cornell.scene
# image size and samples: the paper's 1024x768 with 2x2 subpixels
SIZE ?= 1024x768
WIDTH ?= $(word 1,$(subst x, ,$(SIZE)))
HEIGHT ?= $(word 2,$(subst x, ,$(SIZE)))
SUBPIXELS ?= 2
# the paper's grid: emitted photons P_e x nearest photons n x both methods
PHOTONS ?= 50000 100000 500000
NNS ?= 10 20 50 100
METHODS ?= conventional precomputed
REPEATS ?= 3
# threads per render: 1 as in the paper; empty: all cores (--threads 0)
THREADS ?= 1
# the renderer the runs use (copy build/photonmap aside to pin it during a
# long run; a file PM.commit beside the copy is quoted as its provenance)
PM ?= $(BUILD)/photonmap
# a variant: extra render options PM_ARGS, cells in their own directory TAG;
# CONV_CELLROOT is where the ratio's conventional cells are
TAG ?=
PM_ARGS ?=
# the reference EXR of the error columns (default: found in reference/)
REF ?=
TABLE ?= $(RESULTS)/table1

# derived names (not settings)
T_ARG := $(if $(strip $(THREADS)),$(strip $(THREADS)),0)
T_LABEL := $(if $(strip $(THREADS)),t$(strip $(THREADS)),tall)
CELLROOT := $(RESULTS)/cells/$(WIDTH)x$(HEIGHT)-s$(SUBPIXELS)-$(T_LABEL)$(if $(strip $(TAG)),-$(strip $(TAG)))
CONV_CELLROOT ?= $(CELLROOT)

# make resolution
RES_SIZES ?= 256x192 512x384 1024x768
RES_TARGETS ?= 0.05 0.03 0.02 0.015 0.01 0.0075
RES_REF_PHOTONS ?= 2000000
RES_REF_NN ?= 200
RES_REPEATS ?= $(REPEATS)
RES_REF ?= ours

# make figures
FIG_SIZE ?= 1024x768

# make bench
BENCH_BIN := $(BUILD)/bench/bench

# make sweep-slurm (experiments/slurm.mk): the tasks, from a file of make
# targets (TASKS) or from a target's prerequisites (SWEEP); where the task
# list, the sbatch script and the logs go; extra #SBATCH options (words
# without spaces, e.g. "--time=2:00:00 --cpus-per-task=1 --partition=short")
TASKS ?=
SWEEP ?=
SLURM_DIR ?= $(BUILD)/slurm
SBATCH_OPTS ?=
