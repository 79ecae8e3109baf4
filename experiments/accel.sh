#!/usr/bin/env bash
# accel.sh: what the BVH (renderer/bvh.c) buys, and from how many shapes on
# (the SCENE_BVH_MIN_SHAPES threshold of renderer/scene.h). Renders with
# `--accel linear` and `--accel bvh`, one thread, and prints the photon-pass
# (trace) and eye-pass (render) times from --stats, the median of REPS runs,
# as a Markdown table; also checks that both images are bit-identical.
#   bash experiments/accel.sh [OUT.md]     (default: stdout)
# Knobs (environment): REPS (3), PM (build/photonmap), SIZE (1024x768),
# PHOTONS (500000), NN (100), METHOD (precomputed).
set -euo pipefail
cd "$(dirname "$0")/.."
PM=${PM:-build/photonmap}
REPS=${REPS:-3} SIZE=${SIZE:-1024x768} PHOTONS=${PHOTONS:-500000} NN=${NN:-100} METHOD=${METHOD:-precomputed}
W=${SIZE%x*} H=${SIZE#*x}
TMP=$(mktemp -d /tmp/accel.XXXXXX)
trap 'rm -rf "$TMP"' EXIT

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

# median of the numbers on stdin
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# run SCENE ACCEL: "trace render" medians over REPS runs; the image of the
# last run in $TMP/ACCEL.exr
run() {
  local scene=$1 accel=$2 r
  for r in $(seq 1 "$REPS"); do
    "$PM" render "$scene" --accel "$accel" --method "$METHOD" --photons "$PHOTONS" --nn "$NN" \
      --width "$W" --height "$H" --threads 1 --quiet -o "$TMP/$accel.exr" --stats "$TMP/$accel-$r.json"
  done
  for f in trace render; do
    for r in $(seq 1 "$REPS"); do
      sed -n "s/.*\"time_s\": {.*\"$f\": *\([0-9.e+-]*\).*/\1/p" "$TMP/$accel-$r.json"
    done | median
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
  echo "Ray casting: linear loop vs BVH (\`bash experiments/accel.sh\`), $METHOD, P_e = $PHOTONS, n = $NN,"
  echo "${W}x$H with 2x2 subpixels, 1 thread, median of $REPS runs; seconds from --stats (wall clock)."
  echo "Machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start; commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')."
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
} > "${1:-/dev/stdout}"
