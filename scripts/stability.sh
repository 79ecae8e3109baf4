#!/usr/bin/env bash
# stability.sh: regenerates the case table of results/stability.md (issue 6).
# Every extreme is rendered with build/photonmap --stats (small images and
# photon counts, about a minute on 2 cores); the table reports the exit code,
# photons stored, non-finite pixels and empty estimates from the stats JSON,
# the mean radiance from the EXR (oiiotool --printstats) and a ratio against
# the baseline where one is expected. Estimator-level cases (coincident
# photons, too few or none in range, no agreeing representative) are exact
# unit tests in tests/unit/test_stability.c; their status is reported too.
#   bash scripts/stability.sh > build/stability-table.md
set -u
cd "$(dirname "$0")/.."
PM=${PM:-build/photonmap}
W=$(mktemp -d /tmp/pm-stability.XXXXXX)
trap 'rm -rf "$W"' EXIT
BASE=(--photons 20000 --nn 20 --width 64 --height 48 --quiet)
P0=12.566371

scale_scene() { # S: scenes/cornell.scene with every length times S
  awk -v s="$1" '
    /^[ \t]*#/ || NF == 0 { print; next }
    { out = ""; mode = 0
      for (i = 1; i <= NF; i++) {
        w = $i
        if (w ~ /^#/) break
        if (w == "position" || w == "look_at" || w == "corner" || w == "edge1" || w == "edge2" || w == "center") { mode = 3; out = out " " w; continue }
        if (w == "radius") { mode = 1; out = out " " w; continue }
        if (mode > 0 && w ~ /^[-+.0-9]/) { w = sprintf("%.17g", w * s); mode-- } else mode = 0
        out = out " " w }
      print substr(out, 2) }' scenes/cornell.scene
}
power_scene() { sed "s/power $P0 $P0 $P0/power $1 $1 $1/" "${2:-scenes/cornell.scene}"; }
jget() { sed -n "s/^ *\"$1\": \([^,]*\),*$/\1/p" "$2" | head -n 1; }
mean() { # EXR [FACTOR]: mean radiance over the 3 channels (the image is divided
  # by FACTOR first, since oiiotool prints fixed-point statistics)
  [ -s "$1" ] || { echo "-"; return; }
  local f=${2:-1}
  oiiotool "$1" --mulc "$(awk -v f="$f" 'BEGIN { printf "%.17g", 1 / f }')" --printstats 2>/dev/null |
    awk -v f="$f" '/Stats Avg/ { printf "%.6g", f * ($3 + $4 + $5) / 3 }'
}

BASELINE=
echo "| case | command (beyond the defaults below) | exit | stored | non-finite | empty est. | depth-limit hits | mean L | ratio | verdict |"
echo "|---|---|---|---|---|---|---|---|---|---|"
# row NAME EXPECT-RATIO-FACTOR SCENE VERDICT-RULE options...
#   factor: the mean is divided by factor x baseline (empty: no ratio)
row() {
  local name=$1 factor=$2 scene=$3 rule=$4; shift 4
  local j="$W/r.json" e="$W/r.exr" rc=0
  rm -f "$j" "$e"
  $PM render "$scene" "${BASE[@]}" "$@" -o "$e" --stats "$j" 2>"$W/err" || rc=$?
  local stored="-" nonfin="-" empty="-" depth="-" m ratio="-"
  if [ -s "$j" ]; then
    stored=$(jget photons_stored "$j"); nonfin=$(jget nonfinite_pixels "$j")
    empty=$(jget empty_estimates "$j"); depth=$(jget eye_depth_limit_hits "$j")
  fi
  m=$(mean "$e" "${factor:-1}")
  [ -z "$BASELINE" ] && BASELINE=$m
  if [ -n "$factor" ] && [ "$m" != "-" ]; then
    ratio=$(awk -v m="$m" -v b="$BASELINE" -v f="$factor" 'BEGIN { printf "%.6f", m / (f * b) }')
  fi
  local msg verdict
  msg=$(head -c 160 "$W/err" | tr '\n|' '  ')
  case $rule in
    ok) [ $rc -eq 0 ] && [ "$nonfin" = 0 ] && verdict=ok || verdict=FAIL ;;
    kept) [ $rc -eq 0 ] && [ "$nonfin" != 0 ] && verdict="ok (kept, non-finite reported)" || verdict=FAIL ;;
    ratio) [ $rc -eq 0 ] && [ "$nonfin" = 0 ] && awk -v r="$ratio" 'BEGIN { exit !(r > 0.999 && r < 1.001) }' && verdict=ok || verdict=FAIL ;;
    black) [ $rc -eq 0 ] && [ "$m" = 0 ] && verdict="ok (black)" || verdict=FAIL ;;
    exit1) [ $rc -eq 1 ] && verdict="ok (refused: $msg)" || verdict=FAIL ;;
    exit2) [ $rc -eq 2 ] && verdict="ok (refused: $msg)" || verdict=FAIL ;;
  esac
  local opts="$*"
  [ "$scene" != scenes/cornell.scene ] && opts="[$(basename "$scene")] $opts"
  echo "| $name | \`${opts:-}\` | $rc | $stored | $nonfin | $empty | $depth | $m | $ratio | $verdict |"
}

C=scenes/cornell.scene
row "baseline (Cornell)" 1 $C ok
row "n = 1" "" $C ok --nn 1
row "n = 1, precomputed" "" $C ok --nn 1 --method precomputed
row "P_e = 200, n = 1000 (> stored)" "" $C ok --photons 200 --nn 1000
row "P_e = 200, n = 100000 (max, >> stored)" "" $C ok --photons 200 --nn 100000
row "P_e = 1" "" $C ok --photons 1
row "P_e = 1, precomputed, n = 1" "" $C ok --photons 1 --nn 1 --method precomputed
row "P_e = 0 (documented black image)" "" $C black --photons 0
row "P_e = 0, precomputed" "" $C black --photons 0 --method precomputed
row "P_e = 0, --direct shadow-rays (direct light only)" "" $C ok --photons 0 --direct shadow-rays
row "no photon within the max radius (R = 1e-6)" "" $C black --max-radius 1e-6
row "no representative agrees (--normal-cos 1)" "" $C black --method precomputed --normal-cos 1
for p in 1e-30 1e30 1e35; do
  power_scene $p > "$W/power-$p.scene"
  row "light power $p" "$(awk -v p=$p -v q=$P0 'BEGIN { printf "%.17g", p / q }')" "$W/power-$p.scene" ratio
done
for s in 1e-3 1e3 1e-15 1e-10 1e10 1e14; do
  scale_scene $s > "$W/scale-$s.scene"
  row "scene scaled by $s (ratio of L s^2)" "$(awk -v s=$s 'BEGIN { printf "%.17g", 1 / (s * s) }')" "$W/scale-$s.scene" ratio
done
scale_scene 1e-20 > "$W/scale-1e-20.scene"
row "scene scaled by 1e-20: L ~ 4e39 > float max" "" "$W/scale-1e-20.scene" exit1
scale_scene 1e-3 | sed "s/power $P0 $P0 $P0/power 1e35 1e35 1e35/" > "$W/hot.scene"
row "power 1e35 and scale 1e-3: L ~ 3e39 > float max" "" "$W/hot.scene" exit1
row "... the same with --allow-nonfinite" "" "$W/hot.scene" kept --allow-nonfinite
# all photons within 1e-5 of the light in a 3.5-unit scene: r clamped at 1e-3 R
cat > "$W/coincident.scene" <<'SC'
camera position 0 1 0.000003 look_at 0 1 -1 up 0 1 0 fov 90
light point position 0 1 0 power 1 1 1
material w lambert rho 0.5 0.5 0.5
sphere center 0 1 0 radius 0.00001 material w
rect corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material w
rect corner -1 0 2.5 edge1 0 2 0 edge2 2 0 0 material w
SC
row "photons (nearly) coincident: all inside a 1e-5 ball, r < clamp" "" "$W/coincident.scene" ok
cat > "$W/grazing.scene" <<'SC'
camera position 0 0 3 look_at 0 0 0 up 0 1 0 fov 90
light point position 0.3 0 1 power 10 10 10
material w lambert rho 0.8 0.8 0.8
material g glass ior 1.5
material m mirror reflectance 1 1 1
rect corner -2 0 -2 edge1 0 0 4 edge2 4 0 0 material w
rect corner -2 0 -2 edge1 4 0 0 edge2 0 2 0 material m
sphere center 0.5 0.5 0 radius 0.5 material g
sphere center -0.6 0.4 0 radius 0.4 material w
SC
row "grazing: camera and light in the floor's plane" "" "$W/grazing.scene" ok --subpixels 3
sed 's/^camera .*/camera position 0.05 0.3 0.35 look_at 0.05 0.3 -1 up 0 1 0 fov 65/' $C > "$W/inglass.scene"
row "camera at the glass sphere's centre" "" "$W/inglass.scene" ok
sed 's/^camera .*/camera position 0.05 0.3 0.1 look_at 0.05 0.3 -1 up 0 1 0 fov 65/' $C > "$W/inglass2.scene"
row "camera inside the glass sphere, near its wall" "" "$W/inglass2.scene" ok
cat > "$W/tir.scene" <<'SC'
camera position 0 0.95 0 look_at 1 0.95 0 up 0 1 0 fov 60
light point position 0 3 0 power 10 10 10
material w lambert rho 0.5 0.5 0.5
material g glass ior 10
sphere center 0 0 0 radius 1 material g
sphere center 0 0 0 radius 5 material w
SC
for d in 0 16 1000; do
  row "TIR chains in an ior-10 ball, --eye-depth $d" "" "$W/tir.scene" ok --eye-depth $d
done
row "P_e = 1e9: map would exceed memory" "" $C exit2 --photons 1000000000
row "P_e = 2e9: map would exceed 2^32-1 photons" "" $C exit2 --photons 2000000000

echo
echo "Defaults of every row: \`${BASE[*]}\` (seed 1, conventional, all cores)."
echo "Ratios: mean radiance / (expected factor x baseline mean); power rows expect p / $P0, scale rows L s^2."
echo
echo "Estimator conventions, exact unit tests (\`build/unit-tests NAME\`):"
echo
for t in stability_nn_one_and_at_stored_count stability_coincident_photons stability_few_or_no_photons_in_range \
         stability_no_agreeing_representative stability_photon_counts stability_light_power_extremes \
         stability_scene_scale stability_grazing_rays stability_camera_inside_glass stability_tir_depth_limit \
         stability_exr_round_trip_of_renders stability_parser_degenerate_sizes; do
  echo "- \`$t\`: $(build/unit-tests "$t" 2>&1 | grep -E '^(ok|FAIL)' | cut -d' ' -f1)"
done
