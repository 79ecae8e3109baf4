#!/usr/bin/env bash
# fuzz.test.sh: the scene parser's fuzz target in CI: every seed in
# tests/fuzz/corpus (broken variants and past findings) replays cleanly, then
# FUZZ_TEST_SECONDS (20) of libFuzzer from those seeds finds nothing. Skipped,
# counted as passed with a note, only when clang's libFuzzer runtime is
# missing. Long runs: `make fuzz FUZZ_SECONDS=600`.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

if ! printf 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n);\nint LLVMFuzzerTestOneInput(const char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' |
     ${FUZZ_CC:-clang} -fsanitize=fuzzer -x c - -o "$TMP/probe" >/dev/null 2>&1; then
  echo "note: clang with the libFuzzer runtime (libclang-rt-dev) is missing: fuzzing skipped"
  skip "fuzz: no libFuzzer runtime"
  finish; exit
fi

check "fuzz: target builds" make -s fuzz-build
FZ=build/fuzz_scene
check "fuzz: every committed seed and past finding replays cleanly" $FZ -runs=0 tests/fuzz/corpus
fuzz_briefly() {
  mkdir -p "$TMP/corpus" "$TMP/artifacts"
  $FZ -max_total_time="${FUZZ_TEST_SECONDS:-20}" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
      -dict=tests/fuzz/scene.dict -artifact_prefix="$TMP/artifacts/" -print_final_stats=1 \
      "$TMP/corpus" tests/fuzz/corpus > "$TMP/fuzz.log" 2>&1
  local rc=$?
  grep -E '^stat::number_of_executed_units|^Done' "$TMP/fuzz.log"
  if [ $rc -ne 0 ] || [ -n "$(ls -A "$TMP/artifacts")" ]; then
    tail -n 30 "$TMP/fuzz.log"; ls -A "$TMP/artifacts"
    # keep the finding where a developer can reach it
    mkdir -p build/fuzz-artifacts && cp "$TMP/artifacts"/* build/fuzz-artifacts/ 2>/dev/null
    return 1
  fi
}
check "fuzz: ${FUZZ_TEST_SECONDS:-20} s of libFuzzer find nothing" fuzz_briefly
grep -E '^stat::number_of_executed_units' "$TMP/fuzz.log" | sed 's/^/note: /'
finish
