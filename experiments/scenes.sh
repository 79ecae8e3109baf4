#!/usr/bin/env bash
# scenes.sh: the driver behind `make scenes` (experiments/scenes.mk). Owns
# the loop over scenes: per scene it makes our converged reference at
# SCENES_SIZE, runs `make reproduce-table` for that scene into
# RESULTS/scenes/*-<scene>.*, then hands every scene's tables to
# experiments/analysis/scenes.py.
set -euo pipefail
: "${RESULTS:?}" "${SCENES:?}" "${SCENES_SIZE:?}" "${SCENES_SEEDS:?}"
MAKE=${MAKE:-make}
PYTHON=${PYTHON:-/usr/bin/python3}
out=$RESULTS/scenes
mkdir -p "$out"
args=()
for scene in $SCENES; do
  name=$(basename "$scene" .scene)
  ref=$($MAKE --no-print-directory -s print-res-ref-dir SCENE="$scene")/$SCENES_SIZE.exr
  $MAKE --no-print-directory "$ref" SCENE="$scene"
  $MAKE --no-print-directory reproduce-table SCENE="$scene" SIZE="$SCENES_SIZE" SEEDS="$SCENES_SEEDS" REF="$ref" REF_FAST= \
    TABLE="$out/table-$name" RUNS_CSV="$out/runs-$name.csv" CELLS_CSV="$out/cells-$name.csv" \
    EQUAL_ERROR="$out/equal-error-$name" PHOTONS="$PHOTONS" NNS="$NNS" METHODS="$METHODS" ESTIMATES="$ESTIMATES" \
    THREADS="$THREADS" PM="$PM"
  args+=(--scene "$scene" "$out/table-$name.csv" "$out/runs-$name.csv" "$out/equal-error-$name.csv" "$ref")
done
"$PYTHON" -m experiments.analysis.scenes "${args[@]}" --cell "$SCENES_CELL" --size "$SCENES_SIZE" \
  --ref-photons "$RES_REF_PHOTONS" --ref-nn "$RES_REF_NN" --ref-seed "$RES_REF_SEED" \
  --grid "P_e in {$PHOTONS} x n in {$NNS} x {$METHODS} x estimates {$ESTIMATES}, seeds 1..$SCENES_SEEDS, threads: ${THREADS:-all}" \
  --figures "$RESULTS/figures" --out "$RESULTS/scenes"
