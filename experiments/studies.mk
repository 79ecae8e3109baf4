# studies.mk: Table 1 declared for the make mechanism of experiments/study.mk
# (one make target per render, one analysis call), which only evaluate.mk
# still uses (its own grids; nothing reads table1's variables). Knobs and
# defaults: experiments/config.mk. Every other study target runs on
# Snakemake (experiments/studies.yaml, experiments/snakemake.mk).

# ---- Table 1: the paper's grid on SCENE at SIZE (a variant: TAG, PM_ARGS, CONV_RUNROOT)
table1_SCENE = $(SCENE)
table1_SIZE = $(SIZE)
table1_SEEDS = $(SEEDS)
table1_PHOTONS = $(PHOTONS)
table1_NNS = $(NNS)
table1_METHODS = $(METHODS)
table1_ESTIMATES = $(ESTIMATES)
table1_PM_ARGS = $(PM_ARGS)
table1_TAG = $(TAG)
table1_CONV = $(CONV_RUNROOT)
table1_REF = $(REF_FILE)
table1_REF_FAST = $(REF_FAST_FILE)
table1_NO_REF = none of $(SCENE) at $(SIZE) in reference/$(SCENE_NAME)/: give REF=FILE.exr (a converged render of the scene at $(SIZE)), or run `make scenes SCENES=$(SCENE) SIZE=$(SIZE)`, which renders its own converged reference
table1_RUNS_CSV = $(RUNS_CSV)
table1_CELLS_CSV = $(CELLS_CSV)
table1_TABLE = $(TABLE)
table1_EQUAL_ERROR = $(EQUAL_ERROR)
$(eval $(call study,table1))
# the names the other files use
RUNROOT := $(table1_RUNROOT)
RUN_FILES := $(table1_RUN_FILES)
