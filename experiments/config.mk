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
# the reference's --seed: one no grid uses (photon i of seed s is the same
# path whatever P_e, so a reference rendered with a grid seed would share its
# first photons with that seed's renders and flatter their error)
RES_REF_SEED ?= 1000000
# where our high-photon reference renders go, one <WxH>.exr per size
RES_REF_DIR = $(RESULTS)/runs/$(SCENE_NAME)-refhigh-p$(RES_REF_PHOTONS)-n$(RES_REF_NN)-s$(SUBPIXELS)-seed$(RES_REF_SEED)

# make scenes: every scene's grid at a smaller size, against our own
# converged render of it (RES_REF_PHOTONS, RES_REF_NN); SCENES_CELL is the
# (P_e, n) of the difference images
SCENES ?= $(filter-out scenes/furnace.scene,$(wildcard scenes/*.scene))
SCENES_SIZE ?= 512x384
SCENES_SEEDS ?= 3
SCENES_CELL ?= p100000-n50

# make figures (experiments/figures.mk): drawn from the grid's TABLE.csv,
# RUNS_CSV and CELLS_CSV (their size, seeds, reference) and the renders
# RUNS_CSV names. FIG3_CELLS: the cells of Figure 3 as P_e:n, the first
# FIG3_PAPER_CELLS of them the paper's, the rest controls; FIG_SEED: the
# seed whose images are shown; FIG3_CROP: the 1:1 crop WxH+X+Y, given for
# FIG3_CROP_AT and scaled to the grid's size; FIG_ERROR_BLOCK: the error
# maps' block size in pixels; FIG_REF: the reference (empty: the one in
# CELLS_CSV); FIG_TIME: the time shown (cpu_s or total_s).
FIGURES ?= $(RESULTS)/figures
FIG3_CELLS ?= 50000:10 100000:100 500000:100 50000:100 500000:10
FIG3_PAPER_CELLS ?= 3
FIG_SEED ?= $(firstword $(SEED_LIST))
FIG3_CROP ?= 384x288+150+440
FIG3_CROP_AT ?= 1024x768
FIG_ERROR_BLOCK ?= 2
FIG_REF ?=
FIG_TIME ?= $(EE_TIME)
# Figure 2: one precomputed render of SCENE at WIDTHxHEIGHT with
# --dump-reps (P_e FIG2_PHOTONS, n FIG2_NN, seed FIG_SEED); the plane drawn
# (FIG2_PLANE: the normal axis, at that coordinate's minimum: z = the back
# wall, y = the floor) and the window on it (u0 u1 v0 v1, u and v the other
# two axes in x, y, z order)
FIG2_PHOTONS ?= 50000
FIG2_NN ?= 10
FIG2_PLANE ?= z
FIG2_WINDOW ?= -0.4 0.2 1.0 1.45
FIG2_DIR = $(RESULTS)/runs/fig2-$(SCENE_NAME)-$(WIDTH)x$(HEIGHT)-s$(SUBPIXELS)-p$(FIG2_PHOTONS)-n$(FIG2_NN)-seed$(FIG_SEED)

# make rep-study (experiments/repstudy.mk): the representative rules run
# besides the renderer's default (everyK: --rep-every K; countN: --rep-count
# N; shared: --rep-tree shared), precomputed only, paper estimate, REP_SEEDS
# seeds each, compared with the untagged grid's conventional renders;
# outputs REP_STUDY.md, .csv, -cells.csv and FIGURES/rep-study.png.
# count1100000: the fixed count that fits the paper's slopes (rep-study.md)
REP_RULES ?= every1 every2 every8 every16 shared count1100000
# 3 seeds per rule (the slopes are fitted over every seed's render, and a
# rule's cost varies little from seed to seed): about 10 minutes
REP_SEEDS ?= 3
REP_STUDY ?= $(RESULTS)/rep-study

# make caustic (experiments/caustic.mk): the Figure 3 cells' photon counts
# and n on the caustic scene (the glass sphere lifted so its caustic is in
# view; scenes/caustic.scene if there is one, else reference/caustic.scene)
# at CAUSTIC_SIZE, both methods and ESTIMATES, CAUSTIC_SEEDS seeds; the
# caustic window CAUSTIC_WINDOW given at CAUSTIC_WINDOW_AT
# (tests/povray.test.sh); reference CAUSTIC_REF (default: the POV-Ray render
# of that scene and size in reference/); outputs CAUSTIC.md, .csv,
# CAUSTIC-{runs,cells,table1}.* and FIGURES/caustic.png
CAUSTIC_SCENE ?= $(firstword $(wildcard scenes/caustic.scene reference/caustic.scene))
CAUSTIC_SIZE ?= 128x96
CAUSTIC_PHOTONS ?= 50000 100000 500000
CAUSTIC_NNS ?= 10 100
CAUSTIC_SEEDS ?= 5
CAUSTIC_WINDOW ?= 24x20+52+76
CAUSTIC_WINDOW_AT ?= 128x96
CAUSTIC_REF ?=
CAUSTIC ?= $(RESULTS)/caustic

# make estimator-bias: the analytic scene, every n, method and estimate
BIAS_SCENE ?= scenes/furnace.scene
BIAS_NNS ?= 2 3 5 10 20 50 100 200
BIAS_SEEDS ?= 60
BIAS_PHOTONS ?= 50000
BIAS_SIZE ?= 48x36
BIAS_DIR ?= $(RESULTS)/runs/estimator-bias
BIAS_OUT ?= $(RESULTS)/estimator-bias

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
