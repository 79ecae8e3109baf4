#!/usr/bin/env bash
# accel.test.sh: experiments/accel.sh (`make accel`) on a tiny instance: its
# 8 rows (cornell, cornell with 1-6 boxes, slabs, library), every pair of
# images identical, the header naming the knobs' values, the file written
# under a temporary name and renamed; controls: a study knob it does not read
# (SIZE, REPEATS) and a malformed ACCEL_SIZE are refused, exit 2, and leave
# no file.
cd "$(dirname "$0")/.." || exit 1
. tests/lib.sh

if [ ! -x "$PM" ] || ! command -v taskset > /dev/null; then
  echo "skipped: accel.sh needs $PM and taskset"
  echo "0 passed, 0 failed, 1 skipped"
  exit 0
fi

tiny() { # env assignments...: accel.sh on a 16x12 image, 2000 photons, one repeat
  env ACCEL_SIZE=16x12 ACCEL_PHOTONS=2000 ACCEL_NN=10 ACCEL_REPEATS=1 PM="$PM" "$@" bash experiments/accel.sh "$TMP/accel.md"
}
check "accel.sh: 8 rows, every pair of images identical, the knobs in the header" bash -c "
  $(declare -f tiny); TMP='$TMP'; PM='$PM'; tiny || exit 1
  test \$(grep -c '^| .* | yes |\$' '$TMP/accel.md') -eq 8 && ! grep -q '| NO |' '$TMP/accel.md' &&
  grep -q 'P_e = 2000, n = 10,' '$TMP/accel.md' && grep -q '^16x12 with 2x2' '$TMP/accel.md' &&
  grep -q -- '--repeats 1' '$TMP/accel.md' && test ! -e '$TMP/accel.md.tmp'"
rm -f "$TMP/accel.md"
for bad in SIZE=16x12 REPEATS=2; do
  check "control: $bad (a study knob accel does not read) is refused, exit 2, no file" bash -c "
    $(declare -f tiny); TMP='$TMP'; PM='$PM'
    tiny $bad 2> '$TMP/err'; rc=\$?
    test \$rc -eq 2 && grep -q 'is not a knob of make accel' '$TMP/err' && test ! -e '$TMP/accel.md'"
done
check "control: a malformed ACCEL_SIZE is refused, exit 2, no file" bash -c "
  $(declare -f tiny); TMP='$TMP'; PM='$PM'
  tiny ACCEL_SIZE=16by12 2> '$TMP/err'; rc=\$?
  test \$rc -eq 2 && grep -q \"ACCEL_SIZE '16by12' is not WIDTHxHEIGHT\" '$TMP/err' && test ! -e '$TMP/accel.md'"
finish
