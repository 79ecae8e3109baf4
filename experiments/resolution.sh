#!/usr/bin/env bash
# resolution.sh: the driver behind `make resolution` (experiments/resolution.mk).
# Owns the loop over sizes: per size it picks the reference, runs
# `make reproduce-table` for that size into RESULTS/resolution/*-<size>.*,
# then hands the per-size tables to experiments/analysis/resolution.py.
set -euo pipefail
: "${RESULTS:?}" "${RES_SIZES:?}" "${RES_TARGETS:?}" "${RES_SEEDS:?}" "${RES_REF_DIR:?}"
MAKE=${MAKE:-make}
PYTHON=${PYTHON:-/usr/bin/python3}
out=$RESULTS/resolution
mkdir -p "$out"
size_args=()
for s in $RES_SIZES; do
  ref="" fast=""
  if [ "${RES_REF:-ours}" = pov ]; then
    ref=$(bash experiments/findref.sh "$s" "${SCENE:-scenes/cornell.scene}")
    fast=$(bash experiments/findref.sh --fast "$s" "${SCENE:-scenes/cornell.scene}")
  fi
  if [ -n "$ref" ]; then
    desc="POV-Ray \`$ref\`"
  else
    ref=$RES_REF_DIR/$s.exr
    $MAKE --no-print-directory "$ref"
    why="RES_REF=ours: one kind of reference at every size"
    [ "${RES_REF:-ours}" = pov ] && why="no POV-Ray reference of this size in reference/"
    desc="ours: conventional, P_e=$RES_REF_PHOTONS, n=$RES_REF_NN, seed $RES_REF_SEED (no grid render uses it), same scene and settings, \`$ref\` ($why)"
  fi
  $MAKE --no-print-directory reproduce-table SIZE="$s" SEEDS="$RES_SEEDS" REF="$ref" REF_FAST="$fast" \
    TABLE="$out/table-$s" RUNS_CSV="$out/runs-$s.csv" CELLS_CSV="$out/cells-$s.csv" EQUAL_ERROR="$out/equal-error-$s" \
    PHOTONS="$PHOTONS" NNS="$NNS" METHODS="$METHODS" ESTIMATES="$ESTIMATES" THREADS="$THREADS" PM="$PM"
  size_args+=(--size "$s" "$out/table-$s.csv" "$desc")
done
"$PYTHON" -m experiments.analysis.resolution "${size_args[@]}" --targets "$RES_TARGETS" --time "${EE_TIME:-cpu_s}" \
  --grid "P_e in {$PHOTONS} x n in {$NNS} x {$METHODS} x estimates {$ESTIMATES}, seeds 1..$RES_SEEDS, threads: ${THREADS:-all}" \
  --out "$RESULTS/resolution.md"
