# config.mk: every variable the experiment targets share, in one place
# (included by the top Makefile before experiments/*.mk). Each can be set on
# the command line, e.g. `make reproduce-table SIZE=256x192 SEEDS=3`.

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
# radiance estimates: paper = the paper's estimator (renderer default);
# corrected = the renderer's --bias-correction
ESTIMATES ?= paper corrected
# every cell is rendered once per seed (--seed 1..SEEDS, or the list
# SEED_LIST); the seeds are also the timing repeats
SEEDS ?= 5
SEED_LIST ?= $(shell seq 1 $(SEEDS))
# threads per render: 1 as in the paper; empty: all cores (--threads 0)
THREADS ?= 1
# the renderer the runs use (copy build/photonmap aside to pin it during a
# long run; a file PM.commit beside the copy is quoted as its provenance)
PM ?= $(BUILD)/photonmap
# a variant: extra render options PM_ARGS, runs in their own directory TAG;
# CONV_RUNROOT is where the conventional runs that the precomputed ones are
# compared with live (default: the same directory)
TAG ?=
PM_ARGS ?=
# the reference EXR of the error columns (default: the POV-Ray render of the
# scene at SIZE in reference/, experiments/findref.sh); REF_FAST: the
# fast-quality POV-Ray render whose error against the reference is the
# reference's floor (default: found beside the default reference)
REF ?=
REF_FAST ?=
# outputs
TABLE ?= $(RESULTS)/table1$(TAG_SUFFIX)
RUNS_CSV ?= $(RESULTS)/runs$(TAG_SUFFIX).csv
CELLS_CSV ?= $(RESULTS)/cells$(TAG_SUFFIX).csv
EQUAL_ERROR ?= $(RESULTS)/equal-error$(TAG_SUFFIX)
# equal-error speed-up: relMSE targets ("auto": five inside the range both
# methods' fronts reach), the time it compares (cpu_s: user+system CPU
# seconds of the process, robust on a shared machine with one thread;
# total_s: the renderer's wall clock), bootstrap resamples (also for the
# table's ratio intervals) and the bootstrap's random seed
EE_TARGETS ?= auto
EE_TIME ?= $(if $(filter 1,$(strip $(THREADS))),cpu_s,total_s)
BOOTSTRAP ?= 2000
BOOTSTRAP_SEED ?= 1
# the analysis layer runs on Debian's python3 (numpy, scipy, pandas, OIIO)
PYTHON ?= /usr/bin/python3

# derived names (not settings)
TAG_SUFFIX = $(if $(strip $(TAG)),-$(strip $(TAG)))
T_ARG = $(if $(strip $(THREADS)),$(strip $(THREADS)),0)
T_LABEL = $(if $(strip $(THREADS)),t$(strip $(THREADS)),tall)
SCENE_NAME = $(basename $(notdir $(SCENE)))
RUNROOT = $(RESULTS)/runs/$(SCENE_NAME)-$(WIDTH)x$(HEIGHT)-s$(SUBPIXELS)-$(T_LABEL)$(TAG_SUFFIX)
CONV_RUNROOT ?= $(RUNROOT)
REF_FILE = $(or $(REF),$(shell bash experiments/findref.sh $(WIDTH)x$(HEIGHT) $(SCENE)))
REF_FAST_FILE = $(or $(REF_FAST),$(if $(REF),,$(shell bash experiments/findref.sh --fast $(WIDTH)x$(HEIGHT) $(SCENE))))

# REPEATS is gone: the seeds are the repeats
ifneq ($(origin REPEATS),undefined)
$(error REPEATS was replaced by SEEDS: every seed is a timed run (make reproduce-table SEEDS=$(REPEATS)))
endif

# make resolution
RES_SIZES ?= 256x192 512x384 1024x768
RES_TARGETS ?= 0.05 0.03 0.02 0.015 0.01 0.0075
RES_REF_PHOTONS ?= 2000000
RES_REF_NN ?= 200
RES_SEEDS ?= $(SEEDS)
RES_REF ?= ours
# where our high-photon reference renders go, one <WxH>.exr per size
RES_REF_DIR = $(RESULTS)/runs/$(SCENE_NAME)-refhigh-p$(RES_REF_PHOTONS)-n$(RES_REF_NN)-s$(SUBPIXELS)

# make scenes: every scene's grid at a smaller size, against our own
# converged render of it (RES_REF_PHOTONS, RES_REF_NN); SCENES_CELL is the
# (P_e, n) of the difference images
SCENES ?= $(filter-out scenes/furnace.scene,$(wildcard scenes/*.scene))
SCENES_SIZE ?= 512x384
SCENES_SEEDS ?= 3
SCENES_CELL ?= p100000-n50

# make figures
FIG_SIZE ?= 1024x768

# make estimator-bias: the analytic scene, every n, method and estimate
BIAS_SCENE ?= scenes/furnace.scene
BIAS_NNS ?= 2 3 5 10 20 50 100 200
BIAS_SEEDS ?= 20
BIAS_PHOTONS ?= 50000
BIAS_SIZE ?= 48x36
BIAS_DIR ?= $(RESULTS)/runs/estimator-bias
BIAS_OUT ?= $(RESULTS)/estimator-bias

# make bench
BENCH_BIN := $(BUILD)/bench/bench
