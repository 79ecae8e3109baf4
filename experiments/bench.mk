# `make bench`: the performance benchmark (not a test). Builds
# build/bench/bench (experiments/bench/bench.c on the renderer objects, plus
# nanoflann behind experiments/bench/nano.cpp, FLANN behind flann.cpp:
# its headers pull in lz4 for serialisation, hence -llz4) and writes results/bench/bench.md
# via experiments/bench/run.sh (BENCH_REPS, BENCH_HEAVY_REPS tune it).

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
	bash experiments/bench/run.sh

# `make bench-quick`: the kNN against FLANN, cKDTree and nanoflann alone, in
# about a minute, on stdout (results/bench.md untouched).
.PHONY: bench-quick
bench-quick: bench-bin
	bash experiments/bench/run.sh --quick

# `make bench-peers`: the kNN against FLANN, cKDTree and nanoflann alone, both
# query streams, k = 10 and 100, written to results/bench/peers.md.
.PHONY: bench-peers
bench-peers: bench-bin
	bash experiments/bench/run.sh --peers
