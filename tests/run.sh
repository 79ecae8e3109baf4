#!/usr/bin/env bash
# The test runner behind `make test` and `make check`.
#   bash tests/run.sh          (make test) the unit tests, the same unit tests
#       under AddressSanitizer + UndefinedBehaviorSanitizer, then every
#       tests/*.test.sh script (tests/pytest.test.sh: one `pytest tests/`),
#       then the command-line and hostile-input scripts again against
#       build/san/photonmap (photonmap itself under ASan+UBSan).
#   bash tests/run.sh --fast   (make check) the fast tier, under three minutes
#       on two cores: the unit tests, the command line, hostile input,
#       refusals and the pytest tests; nothing renders a study.
# Each part prints "N passed, N failed" (some add ", N skipped": tests that
# cannot run on this machine); this script adds them up, prints the total last
# ("N passed, N failed, N skipped"), and exits non-zero on any failure.
set -u
FAST_PARTS=(tests/cli.test.sh tests/hostile.test.sh tests/refusals.test.sh tests/pytest.test.sh)
fast=0
case ${1:-} in
  --fast) fast=1 ;;
  "") ;;
  *) echo "usage: bash tests/run.sh [--fast]" >&2; exit 2 ;;
esac
cd "$(dirname "$0")/.."
# the test scripts run make themselves: not as part of the make that runs
# this script (its jobserver and flags would leak into their output)
unset MAKEFLAGS MFLAGS MAKELEVEL

total_pass=0
total_fail=0
total_skip=0

run_part() { # name, command...
  local name=$1; shift
  echo "== $name"
  local out rc
  out=$("$@" 2>&1); rc=$?
  printf '%s\n' "$out" | grep -v '^ok ' || true
  local line p f s=0
  line=$(printf '%s\n' "$out" | grep -E '^[0-9]+ passed, [0-9]+ failed' | tail -n 1)
  if [ -z "$line" ]; then
    echo "   $name: no result line (exit $rc): counted as 1 failure"
    total_fail=$((total_fail + 1)); return
  fi
  p=${line%% passed*}; f=${line#*, }; f=${f%% failed*}
  case $line in *skipped*) s=${line##*failed, }; s=${s%% skipped*} ;; esac
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
    echo "   $name: exited $rc with no failed test: counted as 1 failure"
    f=1
  fi
  total_pass=$((total_pass + p)); total_fail=$((total_fail + f)); total_skip=$((total_skip + s))
}

run_part "unit tests" build/unit-tests
if [ "$fast" -eq 1 ]; then
  for t in "${FAST_PARTS[@]}"; do run_part "$t" bash "$t"; done
  echo
  echo "$total_pass passed, $total_fail failed, $total_skip skipped"
  [ "$total_fail" -eq 0 ]; exit
fi
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  run_part "unit tests (ASan+UBSan)" build/unit-tests-san
for t in tests/*.test.sh; do
  [ -e "$t" ] || continue
  run_part "$t" bash "$t"
done
for t in tests/cli.test.sh tests/hostile.test.sh; do
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0} \
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  PM=build/san/photonmap run_part "$t (photonmap under ASan+UBSan)" bash "$t"
done

echo
echo "$total_pass passed, $total_fail failed, $total_skip skipped"
[ "$total_fail" -eq 0 ]
