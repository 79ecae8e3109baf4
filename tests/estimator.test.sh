#!/usr/bin/env bash
# estimator.test.sh: both radiance estimates against the exact radiance of the
# analytic scene (scenes/furnace.scene, L = 1 everywhere), over seeds:
# the paper's conventional estimate follows n/(n-1), both --bias-correction
# estimates are exact, the precomputed paper estimate is more biased than the
# conventional one; each law with a negative control (experiments/
# analysis/estimator_bias.py --check). Then the settings whose estimate has no finite
# mean are refused with exit 2.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

R=$TMP/results
NNS="3 5 10"
SEEDS=8
make -s -j2 estimator-bias-runs RESULTS="$R" NNS="$NNS" SEEDS=$SEEDS PHOTONS=40000 SIZE=48x36 \
  > "$TMP/runs.log" 2>&1 || { echo "renders failed:"; tail -n 20 "$TMP/runs.log"; }
${PYTHON:-/usr/bin/python3} -m experiments.analysis.estimator_bias --dir "$R/runs/estimator-bias" --nns "$NNS" \
  --seeds $SEEDS --photons 40000 --check > "$TMP/check.log" 2>&1
while read -r verdict rest; do
  case $verdict in
    ok) check "$rest" true ;;
    FAIL) check "$rest" false ;;
  esac
done < <(grep -E '^(ok|FAIL) ' "$TMP/check.log")
check "all 20 law checks ran (3 n x 6, and 2 comparisons)" test "$(grep -cE '^(ok|FAIL) ' "$TMP/check.log")" -eq 20

S=scenes/furnace.scene
check "--nn 1 refused: no finite mean" expect_exit 2 "--nn: expected an integer in \[2," $PM render $S --nn 1
check "precomputed --nn 2 refused (paper estimate), saying why" \
  expect_exit 2 "no finite mean .* --bias-correction" $PM render $S --method precomputed --nn 2
check "precomputed --nn 2 --bias-correction runs" $PM render $S --method precomputed --nn 2 --bias-correction --no-output \
  --photons 2000 --width 8 --height 6 --quiet
check "--bias-correction with --rep-every 1 refused" \
  expect_exit 2 "rep-every 1 leaves none" $PM render $S --method precomputed --bias-correction --rep-every 1
check "--bias-correction with --rep-tree shared refused" \
  expect_exit 2 "rep-tree separate" $PM render $S --method precomputed --bias-correction --rep-tree shared
finish
