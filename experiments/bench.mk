# `make bench`: the performance benchmark of issue 7 (not a test). Builds
# build/bench/bench (experiments/bench/bench.c on the renderer objects, plus
# nanoflann behind experiments/bench/nano.cpp) and writes results/bench/bench.md
# via experiments/bench/run.sh (BENCH_REPS, BENCH_HEAVY_REPS tune it).

$(BUILD)/bench/nano.o: experiments/bench/nano.cpp | $(DEPS_TEST)
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -g -Wall -Wextra -c $< -o $@

$(BUILD)/bench/bench.o: experiments/bench/bench.c renderer/*.h | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -c $< -o $@

$(BENCH_BIN): $(LIB_OBJ) $(BUILD)/bench/bench.o $(BUILD)/bench/nano.o
	$(CXX) $(CFLAGS) -o $@ $^ $(LDLIBS)

.PHONY: bench-bin
bench-bin: $(BENCH_BIN) $(BUILD)/photonmap
bench: bench-bin
	bash experiments/bench/run.sh
