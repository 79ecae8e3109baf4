# photonmap: build, test and experiment entry points. `make` builds
# build/photonmap; `make test` runs every test; experiment targets are in
# experiments/*.mk. Missing Debian packages are installed by
# scripts/install-deps.sh (once; guarded by build/.deps-stamp).

CC ?= cc
BUILD := build
DEPS_STAMP := $(BUILD)/.deps-stamp

WARN := -Wall -Wextra -Wpedantic
ifeq ($(CI),true)
WARN += -Werror
endif
ifdef WERROR
WARN += -Werror
endif
EXR_CFLAGS = $(shell pkg-config --cflags OpenEXR 2>/dev/null || echo -I/usr/include/OpenEXR)
CFLAGS_COMMON = -std=c17 -D_POSIX_C_SOURCE=200809L $(WARN) -pthread $(EXR_CFLAGS) -Irenderer
CFLAGS ?= -O2 -g
LDLIBS := -lOpenEXRCore -lpng -lm -pthread
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined

LIB_SRC := $(filter-out renderer/main.c,$(wildcard renderer/*.c))
LIB_OBJ := $(LIB_SRC:renderer/%.c=$(BUILD)/obj/%.o)
SAN_OBJ := $(LIB_SRC:renderer/%.c=$(BUILD)/san/%.o)
TEST_SRC := $(wildcard tests/unit/*.c)
TEST_OBJ := $(TEST_SRC:tests/unit/%.c=$(BUILD)/obj/test_%.o)
TEST_SAN_OBJ := $(TEST_SRC:tests/unit/%.c=$(BUILD)/san/test_%.o)

.PHONY: all deps test unit-tests clean
all: $(BUILD)/photonmap

deps: $(DEPS_STAMP)
$(DEPS_STAMP): scripts/install-deps.sh
	@mkdir -p $(BUILD)
	bash scripts/install-deps.sh
	@touch $@

$(BUILD)/obj/%.o: renderer/%.c renderer/*.h | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -c $< -o $@

$(BUILD)/san/%.o: renderer/%.c renderer/*.h | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(SAN_FLAGS) -c $< -o $@

$(BUILD)/obj/test_%.o: tests/unit/%.c tests/unit/*.h renderer/*.h | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(CFLAGS) -Itests/unit -c $< -o $@

$(BUILD)/san/test_%.o: tests/unit/%.c tests/unit/*.h renderer/*.h | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(SAN_FLAGS) -Itests/unit -c $< -o $@

$(BUILD)/photonmap: $(LIB_OBJ) $(BUILD)/obj/main.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/unit-tests: $(LIB_OBJ) $(TEST_OBJ)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/unit-tests-san: $(SAN_OBJ) $(TEST_SAN_OBJ)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(LDLIBS)

unit-tests: $(BUILD)/unit-tests $(BUILD)/unit-tests-san

# The one test command (README, .ci/run): unit tests, the same under
# ASan+UBSan, command-line tests; ends with "N passed, N failed".
test: all unit-tests
	bash tests/run.sh

clean:
	rm -rf $(BUILD)/obj $(BUILD)/san $(BUILD)/photonmap $(BUILD)/unit-tests $(BUILD)/unit-tests-san

-include experiments/*.mk
-include reference/*.mk
-include tests/fuzz/*.mk
