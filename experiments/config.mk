# config.mk: the variables the make targets outside the studies share, in one
# place (included by the top Makefile before experiments/snakemake.mk). The
# studies' knobs and their defaults (SIZE, SEEDS, SCENE, PHOTONS, NNS, REF,
# TIME_REPEATS, CONV_REF_*, ...) are not here: they are data, declared once in
# experiments/studies.yaml and checked by experiments/studies.py (retired
# names refused with their successor there too).

RESULTS ?= results
# the renderer the targets outside the studies run (make results pins a copy)
PM ?= $(BUILD)/photonmap
# the analysis layer runs on Debian's python3 (numpy, scipy, pandas, OIIO)
PYTHON ?= /usr/bin/python3
STABILITY_DIR = $(RESULTS)/stability
ACCEL_DIR = $(RESULTS)/accel

# make bench
BENCH_BIN := $(BUILD)/bench/bench
# make bench (experiments/bench.mk): the scaling section (bench-scaling:
# emitted photon counts and threads; 50k..20M takes about 10 minutes on two
# idle cores with SCALING_REPEATS) and the two-thread section (bench-threads: counts and pairs of
# 1-thread/2-thread renders, back to back, order alternating).
SCALING_PHOTONS ?= 50000 100000 200000 500000 1000000 2000000 5000000 10000000 20000000
SCALING_THREADS ?= 2
# each scaling render's times: the minimum over this many repeats in its
# process (--repeats; the 20M renders then take about a minute each)
SCALING_REPEATS ?= 3
THREADS_PHOTONS ?= 5000000 20000000
THREADS_PAIRS ?= 3
