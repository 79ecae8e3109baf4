# fuzz.mk: the scene parser's libFuzzer target, included by the
# top Makefile. `make fuzz` builds build/fuzz_scene with clang
# (-fsanitize=fuzzer,address,undefined) and runs it for FUZZ_SECONDS (60)
# from the committed seeds in tests/fuzz/corpus; new inputs go to
# build/fuzz-corpus, crashes to build/fuzz-artifacts/. A crash becomes a
# regression: copy it into tests/fuzz/corpus/ (tests/fuzz.test.sh replays
# every seed) and add a case to tests/unit/test_scene.c.

FUZZ_CC ?= clang
FUZZ_SECONDS ?= 60
FUZZ_JOBS ?= 1
FUZZ_FLAGS := -std=c17 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wpedantic -g -O1 -fno-omit-frame-pointer \
	-fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -Irenderer
FUZZ_SRC := tests/fuzz/fuzz_scene.c renderer/scene.c renderer/shapes.c renderer/bvh.c renderer/utf8.c

.PHONY: fuzz-build
fuzz-build: $(BUILD)/fuzz_scene

$(BUILD)/fuzz_scene: $(FUZZ_SRC) renderer/*.h
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_FLAGS) -o $@ $(FUZZ_SRC) -lm

fuzz: $(BUILD)/fuzz_scene
	@mkdir -p $(BUILD)/fuzz-corpus $(BUILD)/fuzz-artifacts
	$(BUILD)/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
		-dict=tests/fuzz/scene.dict -print_final_stats=1 -artifact_prefix=$(BUILD)/fuzz-artifacts/ \
		$(BUILD)/fuzz-corpus tests/fuzz/corpus
