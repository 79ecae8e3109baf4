#!/usr/bin/env bash
# accel.sh: what the BVH (renderer/bvh.c) buys, and from how many shapes on
# (the SCENE_BVH_MIN_SHAPES threshold of renderer/scene.h). Renders with
# `--accel linear` and `--accel bvh`, one thread, and prints the photon-pass
# (trace) and eye-pass (render) times from --stats, each the minimum over the
# repeats of one process (--repeats ACCEL_REPEATS), as a Markdown table; also checks
# that both images are bit-identical.
#   make accel                             (results/accel/accel.md)
#   bash experiments/accel.sh [OUT.md]     (default: stdout; a file is
#                                           written under a temporary name and renamed)
# Knobs (environment), prefixed like the other scripted targets' (grid.sh's
# GRID_*, scaling.sh's SCALING_*): ACCEL_REPEATS (auto), ACCEL_SIZE
# (1024x768), ACCEL_PHOTONS (500000), ACCEL_NN (100), ACCEL_METHOD
# (precomputed), ACCEL_CPU (first: the lowest CPU this script may run on; a
# number; none): the CPU every render is pinned to (taskset), as the studies
# pin their timed renders (TIME_CPU); PM (build/photonmap). The study knobs
# it does not read (SIZE, PHOTONS, NN, NNS, METHOD, SEEDS, REPEATS) are
# refused when set, exit 2, so that `make accel SIZE=...` does not run the
# defaults unannounced.
set -euo pipefail
cd "$(dirname "$0")/.."
for k in SIZE PHOTONS NN NNS METHOD SEEDS REPEATS; do
  if [ -n "${!k:-}" ]; then
    echo "accel.sh: $k is not a knob of make accel; it reads ACCEL_SIZE, ACCEL_PHOTONS, ACCEL_NN, ACCEL_METHOD and ACCEL_REPEATS" >&2
    exit 2
  fi
done
PM=${PM:-build/photonmap}
. "experiments/pin.sh"
pin_to "${ACCEL_CPU:-first}"
REPEATS=${ACCEL_REPEATS:-auto} SIZE=${ACCEL_SIZE:-1024x768} PHOTONS=${ACCEL_PHOTONS:-500000} NN=${ACCEL_NN:-100}
METHOD=${ACCEL_METHOD:-precomputed}
if ! [[ $SIZE =~ ^[1-9][0-9]*x[1-9][0-9]*$ ]]; then
  echo "accel.sh: ACCEL_SIZE '$SIZE' is not WIDTHxHEIGHT" >&2
  exit 2
fi
W=${SIZE%x*} H=${SIZE#*x}
TMP=$(mktemp -d /tmp/accel.XXXXXX)
OUT=${1:-}
# a failed or killed run leaves neither its scratch nor a half-written OUT.tmp
trap 'rm -rf "$TMP"; if [ -n "$OUT" ]; then rm -f "$OUT.tmp"; fi' EXIT

# cornell.scene with k small boxes (six rectangles each) in the back left
# corner: 9 + 6k shapes, for the threshold
boxes_scene() {
  local k=$1
  grep -v '^#' scenes/cornell.scene
  awk -v k="$k" 'BEGIN {
    for (i = 0; i < k; i++) {
      x = -0.95 + 0.06 * (i % 5); z = -0.95 + 0.06 * int(i / 5); y = 0; a = 0.04
      printf "rect corner %g %g %g edge1 0 %g 0 edge2 0 0 %g material white\n", x, y, z, a, a
      printf "rect corner %g %g %g edge1 0 %g 0 edge2 0 0 %g material white\n", x + a, y, z, a, a
      printf "rect corner %g %g %g edge1 %g 0 0 edge2 0 0 %g material white\n", x, y + a, z, a, a
      printf "rect corner %g %g %g edge1 %g 0 0 edge2 0 0 %g material white\n", x, y, z, a, a
      printf "rect corner %g %g %g edge1 %g 0 0 edge2 0 %g 0 material white\n", x, y, z, a, a
      printf "rect corner %g %g %g edge1 %g 0 0 edge2 0 %g 0 material white\n", x, y, z + a, a, a
    } }'
}

# run SCENE ACCEL: "trace render", each phase's minimum over the repeats of
# one process (the stats' time_s); the image in $TMP/ACCEL.exr
run() {
  local scene=$1 accel=$2 f
  "${pin[@]}" "$PM" render "$scene" --accel "$accel" --method "$METHOD" --photons "$PHOTONS" --nn "$NN" \
    --width "$W" --height "$H" --threads 1 --repeats "$REPEATS" --quiet -o "$TMP/$accel.exr" --stats "$TMP/$accel.json"
  for f in trace render; do
    sed -n "s/.*\"time_s\": {.*\"$f\": *\([0-9.e+-]*\).*/\1/p" "$TMP/$accel.json"
  done | paste -sd' '
}

row() { # label, scene
  local label=$1 scene=$2 n lin bvh same
  n=$(grep -c '^ *\(rect\|sphere\) ' "$scene")
  lin=$(run "$scene" linear)
  bvh=$(run "$scene" bvh)
  same=$(cmp -s "$TMP/linear.exr" "$TMP/bvh.exr" && echo yes || echo NO)
  set -- $lin $bvh
  printf '| %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %s |\n' "$label" "$n" "$1" "$3" "$2" "$4" "$(awk -v a="$2" -v b="$4" 'BEGIN { print a / b }')" "$same"
}

{
  echo "Ray casting: linear loop vs BVH (\`make accel\`, experiments/accel.sh), $METHOD, P_e = $PHOTONS, n = $NN,"
  echo "${W}x$H with 2x2 subpixels, 1 thread; seconds from --stats (wall clock), each phase's minimum over the"
  echo "repeats of one process (\`--repeats $REPEATS\`); $([ "$CPU" = none ] && echo "unpinned" || echo "every render pinned to CPU $CPU")."
  echo "Machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start; commit \`$(git rev-parse --short HEAD 2>/dev/null || echo '?')\`; renderer \`$PM\`."
  echo
  echo "| scene | shapes | photon pass, linear | photon pass, BVH | eye pass, linear | eye pass, BVH | eye pass linear/BVH | images identical |"
  echo "|---|---:|---:|---:|---:|---:|---:|---|"
  row cornell scenes/cornell.scene
  for k in 1 2 3 4 6; do
    boxes_scene "$k" > "$TMP/boxes$k.scene"
    row "cornell + $k boxes" "$TMP/boxes$k.scene"
  done
  row slabs scenes/slabs.scene
  row library scenes/library.scene
} > "${OUT:-/dev/stdout}${OUT:+.tmp}"
if [ -n "$OUT" ]; then mv "$OUT.tmp" "$OUT"; fi
