# `make bench`: the performance benchmark (not a test). Builds
# build/bench/bench (experiments/bench/bench.c on the renderer objects, plus
# nanoflann behind experiments/bench/nano.cpp, FLANN behind flann.cpp:
# its headers pull in lz4 for serialisation, hence -llz4) and writes results/bench/bench.md
# via experiments/bench/run.sh (BENCH_REPS, BENCH_HEAVY_REPS tune it), then
# results/bench/repeats.{md,csv}, repeats-warm.csv (bench-repeats).

$(BUILD)/bench/nano.o: experiments/bench/nano.cpp | $(DEPS_TEST)
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -g -Wall -Wextra -c $< -o $@

$(BUILD)/bench/flann.o: experiments/bench/flann.cpp | $(DEPS_TEST)
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -g -Wall -Wextra -c $< -o $@

$(BUILD)/bench/bench.o: experiments/bench/bench.c renderer/*.h | $(DEPS_TEST)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -c $< -o $@

$(BENCH_BIN): $(LIB_OBJ) $(BUILD)/bench/bench.o $(BUILD)/bench/nano.o $(BUILD)/bench/flann.o
	$(CXX) $(CFLAGS) -o $@ $^ $(LDLIBS) -llz4

.PHONY: bench-bin
bench-bin: $(BENCH_BIN) $(BUILD)/photonmap
bench: bench-bin
	SCALING_PHOTONS="$(SCALING_PHOTONS)" SCALING_THREADS="$(SCALING_THREADS)" SCALING_REPEATS="$(SCALING_REPEATS)" \
	  THREADS_PHOTONS="$(THREADS_PHOTONS)" THREADS_PAIRS="$(THREADS_PAIRS)" PYTHON="$(PYTHON)" \
	  bash experiments/bench/run.sh
	$(PYTHON) -m experiments.analysis.repeats_cost --results $(RESULTS) --out $(RESULTS)/bench/repeats

# `make bench-quick`: the kNN against FLANN, cKDTree and nanoflann alone, in
# about a minute, on stdout (results/bench.md untouched).
.PHONY: bench-quick
bench-quick: bench-bin
	bash experiments/bench/run.sh --quick

# `make bench-scaling` (also run by `make bench`, after the rest, and copied
# into bench.md): each phase's cost and the peak memory per stored photon
# against the emitted photons, with fitted log-log slopes ->
# results/bench/scaling.{csv,md}, results/figures/bench-scaling.png
# (experiments/bench/scaling.sh; SCALING_PHOTONS, SCALING_THREADS,
# SCALING_REPEATS in experiments/config.mk).
.PHONY: bench-scaling
bench-scaling: $(BUILD)/photonmap
	SCALING_PHOTONS="$(SCALING_PHOTONS)" SCALING_THREADS="$(SCALING_THREADS)" SCALING_REPEATS="$(SCALING_REPEATS)" \
	  PYTHON="$(PYTHON)" bash experiments/bench/scaling.sh $(BUILD)/photonmap
# `make bench-peers`: the kNN against FLANN, cKDTree and nanoflann alone, both
# query streams, k = 1, 10 and 100 (ours also by packets of four and stateless),
# written to results/bench/peers.md.
.PHONY: bench-peers
bench-peers: bench-bin
	bash experiments/bench/run.sh --peers

# `make bench-threads`: the two-thread speed-up of the photon pass and the
# build, paired (experiments/bench/threads.sh; THREADS_PHOTONS, THREADS_PAIRS
# in experiments/config.mk) -> results/bench/threads.md; `make bench` runs it
# too and copies it into bench.md.
.PHONY: bench-threads
bench-threads: $(BUILD)/photonmap
	THREADS_PHOTONS="$(THREADS_PHOTONS)" THREADS_PAIRS="$(THREADS_PAIRS)" PYTHON="$(PYTHON)" \
	  bash experiments/bench/threads.sh $(BUILD)/photonmap

# `make bench-repeats` (also run by `make bench`, last): the cost of timing
# with repeats, from the stats files of every render under RESULTS/runs/, per
# study run root (renders, repeats per render, one run against the repeats'
# time, how far the minima lie below the first run and the median per phase),
# and the cost model of `make calibrate` per unit of work (RESULTS/calibrate/
# model.json, or "not measured"), which repeats are warm per process
# -> RESULTS/bench/repeats.{md,csv}, repeats-warm.csv
# (experiments/analysis/repeats_cost.py). Renders nothing: seconds.
.PHONY: bench-repeats
bench-repeats: | $(DEPS_TEST)
	$(PYTHON) -m experiments.analysis.repeats_cost --results $(RESULTS) --out $(RESULTS)/bench/repeats
