# photonmap: the top of the build. Everything a user runs is listed here
# (`make help` prints the list); the rules behind the experiment and
# reference targets live in the files included at the bottom, which share
# the variables of experiments/config.mk. Missing Debian packages are
# installed by scripts/install-deps.sh by tier, once each, when a target
# needs the tier: build (a plain make), test (make test, the experiments,
# bench), cluster (make test's Slurm test); stamps build/.deps-TIER.

CC ?= cc
CXX ?= c++
BUILD := build
DEPS_STAMP := $(BUILD)/.deps-build
DEPS_TEST := $(BUILD)/.deps-test
DEPS_CLUSTER := $(BUILD)/.deps-cluster

WARN := -Wall -Wextra -Wpedantic
ifeq ($(CI),true)
WARN += -Werror
endif
ifdef WERROR
WARN += -Werror
endif
EXR_CFLAGS = $(shell pkg-config --cflags OpenEXR 2>/dev/null || echo -I/usr/include/OpenEXR)
# -fno-math-errno: nothing reads errno after math calls, so sqrt and lrint
# compile to single instructions (results are the same)
CFLAGS_COMMON = -std=c17 -D_POSIX_C_SOURCE=200809L -fno-math-errno $(WARN) -pthread $(EXR_CFLAGS) -Irenderer
CFLAGS ?= -O2 -g
# the release objects (build/obj: build/photonmap, the binary the benchmarks
# time, and the tools) are built without asserts; the unit tests link the
# same sources built with them (build/dbg), and the sanitizer build
# (build/san) keeps them too
RELEASE_FLAGS := -DNDEBUG
LDLIBS := -lOpenEXRCore -lpng -lm -pthread
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined

LIB_SRC := $(filter-out renderer/main.c,$(wildcard renderer/*.c))
LIB_OBJ := $(LIB_SRC:renderer/%.c=$(BUILD)/obj/%.o)
DBG_OBJ := $(LIB_SRC:renderer/%.c=$(BUILD)/dbg/%.o)
SAN_OBJ := $(LIB_SRC:renderer/%.c=$(BUILD)/san/%.o)
TEST_SRC := $(wildcard tests/unit/*.c)
TEST_OBJ := $(TEST_SRC:tests/unit/%.c=$(BUILD)/dbg/test_%.o)
TEST_SAN_OBJ := $(TEST_SRC:tests/unit/%.c=$(BUILD)/san/test_%.o)
# every unit test is a `void test_NAME(void)` in tests/unit/test_*.c; this
# generated list (one X(NAME) per test) is all the runner knows of them
TEST_LIST := $(BUILD)/unit/tests.list.h

# ---- what users run (`make help`: one line each, from the ## comments) ----
.PHONY: calibrate results results-check
.PHONY: all deps test check help clean accel reproduce-table reproduce-runs list-runs figures rep-study caustic resolution estimator-bias scenes stability bench reference reference-small reference-pbrt fuzz sweep-slurm evaluate beyond reproducibility findings bench-threads
all: $(BUILD)/photonmap ## build build/photonmap
deps: $(DEPS_STAMP) $(DEPS_TEST) $(DEPS_CLUSTER) ## install the missing Debian packages of every tier (scripts/install-deps.sh)
test: all unit-tests $(BUILD)/san/photonmap $(DEPS_TEST) $(DEPS_CLUSTER) ## every test; ends with "N passed, N failed, N skipped" (README)
	bash tests/run.sh
check: all $(BUILD)/unit-tests $(DEPS_TEST) ## the fast tier: unit tests, command line, hostile input, refusals, pytest tests/ (under 3 min)
	bash tests/run.sh --fast
reproduce-table: ## Table 1 over SEEDS seeds, both estimates -> results/table1/ (Snakemake: experiments/studies.yaml, experiments/rules/table1.smk)
reproduce-runs: ## only the renders of reproduce-table (Snakemake; resumes)
list-runs: ## print the record path of every render of reproduce-table, one per line
figures: ## Figures 2 and 3 at 1:1, error maps, trade-off, time ratio and phases -> results/figures/ (after reproduce-table; Snakemake: studies.yaml, rules/figures.smk)
rep-study: ## representative rules (REP_RULES) against the paper's cost pattern -> results/rep-study/, figures/rep-study.png
caustic: ## the Fig. 3 cells on the caustic scene, caustic-window error over seeds -> results/caustic/, figures/caustic.png (Snakemake: studies.yaml, rules/caustic.smk)
resolution: ## cheapest settings per output size -> results/resolution/
gather: ## final gathering (--gather N), both methods over P_e x n x N on every scene and cornell's sizes: equal-error and gather-phase speed-ups, best configuration per target -> results/gather/, figures/gather.png (Snakemake: studies.yaml, rules/gather.smk)
estimator-bias: ## both estimators' bias in the analytic scene over n -> results/estimator-bias/ (Snakemake: studies.yaml, rules/bias.smk)
reproducibility: ## Table 1's grid again after Table 1 (run b), then again with a busy loop on the other core (run busy), not interleaved: how far the paired ratios move between runs -> results/reproducibility/
findings: ## results/FINDINGS.md from the results files; checks that README's findings numbers are in results/
scenes: ## the grid on every scene: equal-error speed-up, kNN share, where the error lies -> results/scenes/
beyond: ## the paper's rule, lazy, gated and lazy+gated representatives at equal error per scene and size -> results/beyond/, figures/beyond.png
stability: ## every extreme with its expected value and verdict -> results/stability/stability-extremes.md
accel: ## the BVH against the loop over shapes, photon and eye pass, repeat minima, images compared -> results/accel/accel.md (experiments/accel.sh)
bench: ## kNN (against FLANN, cKDTree, nanoflann), lookup and eye-pass benchmarks -> results/bench/bench.md
bench-quick: ## only the kNN against FLANN, cKDTree and nanoflann, about a minute, on stdout
bench-scaling: ## each phase's cost and peak bytes per stored photon against the photons, log-log slopes -> results/bench/scaling.md (SCALING_PHOTONS)
bench-threads: ## the two-thread speed-up of the photon pass and the build, paired -> results/bench/threads.md (THREADS_PHOTONS, THREADS_PAIRS)
bench-repeats: ## the cost of repeats per study (from every render's stats under runs/) and the cost model per unit of work (results/calibrate/model.json) -> results/bench/repeats.md
bench-peers: ## only the kNN against FLANN, cKDTree and nanoflann, both query streams -> results/bench/peers.md
reference: ## re-render every POV-Ray reference in reference/ (committed; slow)
reference-small: ## the POV-Ray references except the 1024x768 one
reference-pbrt: ## re-render the pbrt-v3 references (needs pbrt: PBRT=path; reference/pbrt/README.md)
fuzz: ## run the scene parser's libFuzzer target for FUZZ_SECONDS (60)
evaluate: ## does the method pay on SCENE=my.scene? pilot, POV-Ray and converged references, grid, verdict -> OUT/report.md (Snakemake: studies.yaml, rules/evaluate.smk)
sweep-slurm: ## a study target's renders on Slurm through Snakemake: SWEEP=TARGET (= make TARGET CLUSTER=slurm)
help: ## this list
	@awk -F':.*## ' '/^[a-z][a-z-]*:.*## / { printf "  make %-17s %s\n", $$1, $$2 }' $(firstword $(MAKEFILE_LIST))
clean: ## remove the build (not results/ or reference/)
	rm -rf $(BUILD)/obj $(BUILD)/dbg $(BUILD)/san $(BUILD)/unit $(BUILD)/photonmap $(BUILD)/unit-tests $(BUILD)/unit-tests-san

results: $(BUILD)/photonmap | $(DEPS_TEST) ## every study regenerated on one renderer, resumable across sessions and machines, each attempt logged -> results/, results/regeneration-log.md (RESULTS_ONLY="T ...", WHY="...")
	@$(PYTHON) -m experiments.regenerate run --results $(RESULTS) $(if $(RESULTS_ONLY),--only $(RESULTS_ONLY)) $(if $(WHY),--why $(call shell_quote,$(WHY)))
results-check: | $(DEPS_TEST) ## every study of the log finished on one renderer's sources, every render under results/runs by it, each study's files naming one commit
	@$(PYTHON) -m experiments.regenerate check --results $(RESULTS)

calibrate: $(BUILD)/photonmap | $(DEPS_TEST) ## this machine's cost model: each phase's time per unit of its work counters, renders at the studies' sizes timed as theirs (TIME_*), checked on held-out renders -> results/calibrate/
	$(PYTHON) -m experiments.calibrate --pm $(PM) --out $(RESULTS)/calibrate

stability: $(BUILD)/photonmap | $(DEPS_TEST)
	@mkdir -p $(STABILITY_DIR)
	$(PYTHON) -m experiments.stability --pm $(PM) > $(STABILITY_DIR)/stability-extremes.md.tmp
	mv $(STABILITY_DIR)/stability-extremes.md.tmp $(STABILITY_DIR)/stability-extremes.md

accel: $(BUILD)/photonmap
	@mkdir -p $(ACCEL_DIR)
	PM=$(PM) bash experiments/accel.sh $(ACCEL_DIR)/accel.md

# ---- the build ----
# provenance.o carries the commit, whether tracked files outside results/ had
# changes, and the flags of its build (the stats' "provenance"); $(BUILD)/.provenance
# changes only when they do, and rebuilds it then
PM_COMMIT := $(shell git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
PM_TREE := $(if $(filter unknown,$(PM_COMMIT)),unknown,$(shell git status --porcelain --untracked-files=no -- . ':!results' 2>/dev/null | grep -q . && echo dirty || echo clean))
PROVENANCE = -DPM_COMMIT='"$(PM_COMMIT)"' -DPM_TREE='"$(PM_TREE)"' -DPM_FLAGS='"$(strip $(1))"'
$(BUILD)/.provenance: FORCE
	@mkdir -p $(BUILD); echo '$(PM_COMMIT) $(PM_TREE) $(CC) $(CFLAGS)' | cmp -s - $@ || echo '$(PM_COMMIT) $(PM_TREE) $(CC) $(CFLAGS)' > $@
$(BUILD)/obj/provenance.o $(BUILD)/dbg/provenance.o $(BUILD)/san/provenance.o: $(BUILD)/.provenance
$(BUILD)/obj/provenance.o: CFLAGS_COMMON += $(call PROVENANCE,$(CFLAGS) $(RELEASE_FLAGS))
$(BUILD)/dbg/provenance.o: CFLAGS_COMMON += $(call PROVENANCE,$(CFLAGS))
$(BUILD)/san/provenance.o: CFLAGS_COMMON += $(call PROVENANCE,$(SAN_FLAGS))
.PHONY: FORCE
$(BUILD)/.deps-%: scripts/install-deps.sh
	@mkdir -p $(BUILD)
	bash scripts/install-deps.sh $*
	@touch $@

$(BUILD)/obj/%.o: renderer/%.c renderer/*.h renderer/*.inc | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) $(RELEASE_FLAGS) -c $< -o $@

$(BUILD)/dbg/%.o: renderer/%.c renderer/*.h renderer/*.inc | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -c $< -o $@

$(BUILD)/san/%.o: renderer/%.c renderer/*.h renderer/*.inc | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(SAN_FLAGS) -c $< -o $@

$(TEST_LIST): $(wildcard tests/unit/test_*.c)
	@mkdir -p $(dir $@)
	sed -n 's/^void test_\([a-z0-9_]*\)(void)$$/X(\1)/p' $(sort $^) > $@.tmp
	mv $@.tmp $@

$(BUILD)/dbg/test_%.o: tests/unit/%.c tests/unit/*.h renderer/*.h $(TEST_LIST) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -Itests/unit -I$(BUILD)/unit -c $< -o $@

$(BUILD)/san/test_%.o: tests/unit/%.c tests/unit/*.h renderer/*.h $(TEST_LIST) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(SAN_FLAGS) -Itests/unit -I$(BUILD)/unit -c $< -o $@

$(BUILD)/photonmap: $(LIB_OBJ) $(BUILD)/obj/main.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# photonmap itself under ASan+UBSan: tests/run.sh runs the command-line and
# hostile-input tests against it too
$(BUILD)/san/photonmap: $(SAN_OBJ) $(BUILD)/san/main.o
	$(CC) $(SAN_FLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/unit-tests: $(DBG_OBJ) $(TEST_OBJ)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/unit-tests-san: $(SAN_OBJ) $(TEST_SAN_OBJ)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(LDLIBS)

.PHONY: unit-tests
unit-tests: $(BUILD)/unit-tests $(BUILD)/unit-tests-san

# ---- rules of the experiment, benchmark, reference and fuzz targets ----
# experiments/config.mk holds every variable they share (read first).
include experiments/config.mk
include experiments/snakemake.mk
include experiments/findings.mk
include experiments/bench.mk
include reference/reference.mk
include tests/fuzz/fuzz.mk
