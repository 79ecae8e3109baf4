# config.mk: every variable the experiment targets share, in one place
# (included by the top Makefile before experiments/snakemake.mk).
# Each can be set on the command line, e.g.
# `make reproduce-table SIZE=256x192 SEEDS=3`. One name per knob: SIZE,
# SEEDS, SCENE, PHOTONS, NNS, REF mean the same for every study target; a
# name a target does not read is refused (below), never silently ignored.

RESULTS ?= results
SCENE ?= scenes/cornell.scene
# image size and samples: the paper's 1024x768 with 2x2 subpixels
SIZE ?= 1024x768
SUBPIXELS ?= 2
# the paper's grid: emitted photons P_e x nearest photons n x both methods
PHOTONS ?= 50000 100000 500000
NNS ?= 10 20 50 100
METHODS ?= conventional precomputed
# radiance estimates: paper = the paper's estimator (renderer default);
# corrected = the renderer's --bias-correction
ESTIMATES ?= paper corrected
# every cell is rendered once per seed (--seed 1..SEEDS); the seeds are also
# the timing repeats
SEEDS ?= 5
# threads per render: 1 as in the paper; empty: all cores (--threads 0)
THREADS ?= 1
# the renderer the runs use (copy build/photonmap aside to pin it during a
# long run; a file PM.commit beside the copy is quoted as its provenance)
PM ?= $(BUILD)/photonmap
# a variant of Table 1: extra render options PM_ARGS, runs in their own
# directory TAG; CONV_RUNROOT is where the conventional runs that the
# precomputed ones are compared with live (default: the same directory)
TAG ?=
PM_ARGS ?=
CONV_RUNROOT ?=
# the reference EXR of the error columns (default: the POV-Ray render of the
# scene at SIZE in reference/SCENE/, experiments/findref.sh: the one with the
# renders' 2x2 subpixel rays where there is one); REF_FAST: the fast-quality
# POV-Ray render of the same sampling whose error against the reference is the
# reference's floor (default: found beside the default reference)
REF ?=
REF_FAST ?=
# equal-error speed-up: relMSE targets ("auto": five inside the range both
# methods' fronts reach; the curve covers the whole common range anyway);
# TIME: the time every study compares (total_s: the renderer's own timer,
# time_s.total, no start-up and no image writing; cpu_s: user+system CPU
# seconds of the process, the secondary column); bootstrap resamples (also
# for the table's ratio intervals) and the bootstrap's random seed
EE_TARGETS ?= auto
TIME ?= total_s
BOOTSTRAP ?= 2000
BOOTSTRAP_SEED ?= 1
# the analysis layer runs on Debian's python3 (numpy, scipy, pandas, OIIO)
PYTHON ?= /usr/bin/python3

# where each study writes (results/README.md is the index)
TAG_SUFFIX = $(if $(strip $(TAG)),-$(strip $(TAG)))
TABLE1_DIR = $(RESULTS)/table1
TABLE = $(TABLE1_DIR)/table1$(TAG_SUFFIX)
RUNS_CSV = $(TABLE1_DIR)/runs$(TAG_SUFFIX).csv
CELLS_CSV = $(TABLE1_DIR)/cells$(TAG_SUFFIX).csv
EQUAL_ERROR = $(TABLE1_DIR)/equal-error$(TAG_SUFFIX)
REP_DIR = $(RESULTS)/rep-study
REP_STUDY = $(REP_DIR)/rep-study
STABILITY_DIR = $(RESULTS)/stability
FIGURES = $(RESULTS)/figures

# derived names (not settings)
T_ARG = $(if $(strip $(THREADS)),$(strip $(THREADS)),0)
T_LABEL = $(if $(strip $(THREADS)),t$(strip $(THREADS)),tall)
SCENE_NAME = $(basename $(notdir $(SCENE)))
WIDTH = $(call size_w,$(SIZE))
HEIGHT = $(call size_h,$(SIZE))
REF_FILE = $(or $(REF),$(shell bash experiments/findref.sh $(SIZE) $(SCENE)))
REF_FAST_FILE = $(or $(REF_FAST),$(if $(REF),,$(shell bash experiments/findref.sh --fast $(SIZE) $(SCENE))))

# names that are gone: each is refused with the one that replaced it
config_renamed := REPEATS=SEEDS SEED_LIST=SEEDS WIDTH=SIZE HEIGHT=SIZE EE_TIME=TIME FIG_TIME=TIME \
  SCENES_SIZE=SIZE SCENES_SEEDS=SEEDS CAUSTIC_SIZE=SIZE CAUSTIC_SEEDS=SEEDS CAUSTIC_PHOTONS=PHOTONS \
  CAUSTIC_NNS=NNS CAUSTIC_SCENE=SCENE CAUSTIC_REF=REF RES_SEEDS=SEEDS REP_SEEDS=SEEDS BIAS_SEEDS=SEEDS \
  BIAS_SIZE=SIZE BIAS_NNS=NNS BIAS_PHOTONS=PHOTONS BIAS_SCENE=SCENE BIAS_DIR=RESULTS \
  RES_REF_PHOTONS=CONV_REF_PHOTONS RES_REF_NN=CONV_REF_NN RES_REF_SEED=CONV_REF_SEEDS
$(foreach r,$(config_renamed),$(if $(filter command line environment,$(origin $(word 1,$(subst =, ,$(r))))),\
  $(error $(word 1,$(subst =, ,$(r))) is gone: every study target reads $(word 2,$(subst =, ,$(r))) (e.g. make scenes SIZE=128x96 SEEDS=2))))

# our converged reference (make evaluate; the studies: studies.yaml;
# experiments/analysis/reference.py): method-neutral, the corrected estimate
# with direct light by CONV_REF_DIRECT at CONV_REF_PHOTONS photons (empty:
# CONV_REF_FACTOR times the grid's largest P_e), n = CONV_REF_NN, the mean of
# the seeds CONV_REF_SEEDS (at least two, none a grid seed), each rendered
# again at half the photons to measure its kernel bias; its noise and bias
# must each be at most CONV_REF_MARGIN of the tightest target it judges
# (reports warn otherwise). At fixed n the kNN noise hardly depends on P_e:
# the factor lowers the bias, the seeds the noise (four: on the L-shaped
# room of tests/evaluate two seeds left 11% of the tightest target)
CONV_REF_PHOTONS ?=
CONV_REF_FACTOR ?= 20
CONV_REF_NN ?= 200
CONV_REF_SEEDS ?= 1000001 1000002 1000003 1000004
CONV_REF_DIRECT ?= shadow-rays
CONV_REF_MARGIN ?= 0.1





# make bench
BENCH_BIN := $(BUILD)/bench/bench


# make bench (experiments/bench.mk): the scaling section (bench-scaling:
# emitted photon counts and threads; 50k..20M takes about 3 minutes on two
# idle cores) and the two-thread section (bench-threads: counts and pairs of
# 1-thread/2-thread renders, back to back, order alternating).
SCALING_PHOTONS ?= 50000 100000 200000 500000 1000000 2000000 5000000 10000000 20000000
SCALING_THREADS ?= 2
THREADS_PHOTONS ?= 5000000 20000000
THREADS_PAIRS ?= 3
