#!/usr/bin/env bash
# refusals.test.sh: the renderer refuses only what it cannot render, says the
# true reason, and warns about what would be silently wrong:
#   - a channel whose radiance underflows next to ordinary ones is written
#     (and counted, flushed_values); an image whose largest radiance is below
#     the float range is refused;
#   - --max-radius at the top of its range renders, the same image as a cap
#     beyond the photons' extent;
#   - a camera far from the origin is refused naming the camera;
#   - the stats of a refused run say "status": "refused" and why;
#   - warnings: photons escaping an open scene, eye paths cut at the depth
#     limit, a camera shut in an opaque sphere (and none for the project's
#     closed scenes: negative controls);
#   - an output name whose extension is not its format's is refused, and so
#     is a render with no output unless --no-output says so.
#   - --gather with --direct photons is refused naming both (direct light
#     would count twice); without --direct it takes shadow rays.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

FAST=(--photons 2000 --nn 10 --width 16 --height 12 --quiet)
ROOM='camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60
material w lambert rho 0.5 0.5 0.5
sphere center 0 1 0 radius 3 material w'

# ---- underflow of one channel, of the whole image ----
printf '%s\nlight point position 0 1 0 power 1e-60 1 1\n' "$ROOM" > "$TMP/red.scene"
red_channel_written() {
  rm -f "$TMP/red.exr" "$TMP/red.json"
  $PM render "$TMP/red.scene" "${FAST[@]}" -o "$TMP/red.exr" --stats "$TMP/red.json" || { echo "exit $?"; return 1; }
  [ -s "$TMP/red.exr" ] && grep -q '"status": "ok"' "$TMP/red.json" &&
  grep -Eq '"flushed_values": [1-9][0-9]*,' "$TMP/red.json" && grep -Eq '"underflow_pixels": [1-9]' "$TMP/red.json" ||
  { cat "$TMP/red.json"; return 1; }
}
check "red power 1e-60 beside green and blue 1: written, exit 0, flushed values counted" red_channel_written
printf 'camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nmaterial w lambert rho 0.5 0.5 0.5
sphere center 0 1 0 radius 1e14 material w\nlight point position 0 1 0 power 1e-30 1e-30 1e-30\n' > "$TMP/weak.scene"
weak_refused() {
  rm -f "$TMP/weak.exr" "$TMP/weak.json"
  expect_exit 2 "^$TMP/weak.scene: the image's largest radiance, .* is below the smallest normal float" \
    $PM render "$TMP/weak.scene" "${FAST[@]}" -o "$TMP/weak.exr" --stats "$TMP/weak.json" &&
  [ ! -e "$TMP/weak.exr" ]
}
check "every channel below the float range: refused, exit 2, no image" weak_refused

# ---- the stats of a refused run ----
refused_stats() {
  weak_refused && grep -q '"status": "refused"' "$TMP/weak.json" &&
  grep -q '"reason": "the image.s largest radiance' "$TMP/weak.json" &&
  /usr/bin/python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); sys.exit(j["status"] != "refused")' \
    "$TMP/weak.json"
}
check "a refused run's stats say \"status\": \"refused\" and the reason" refused_stats
check "a finished run's stats say \"status\": \"ok\"" grep -q '"status": "ok"' "$TMP/red.json"

# ---- --max-radius at the top of its range ----
max_radius_top() { # method
  rm -f "$TMP/top.exr" "$TMP/cap.exr"
  $PM render scenes/cornell.scene "${FAST[@]}" --method "$1" --max-radius 1e30 -o "$TMP/top.exr" \
    --stats "$TMP/top.json" || { echo "exit $?"; return 1; }
  $PM render scenes/cornell.scene "${FAST[@]}" --method "$1" --max-radius 1e3 -o "$TMP/cap.exr" &&
  cmp "$TMP/top.exr" "$TMP/cap.exr" && ! grep -q '"mean_radiance": \[0, 0, 0\]' "$TMP/top.json"
}
check "--max-radius 1e30, conventional: renders, the image of a cap of 1e3" max_radius_top conventional
check "--max-radius 1e30, precomputed: renders, the image of a cap of 1e3 (not black)" max_radius_top precomputed

check "--max-radius 1e30 with fewer photons than n: refused naming the cap, not the light" \
  expect_exit 2 "below the smallest normal float .*: --max-radius 1e\+30 is .* times the photons' extent" \
  $PM render scenes/cornell.scene --photons 5 --nn 50 --width 8 --height 8 --quiet --max-radius 1e30 -o "$TMP/cap5.exr"

# ---- a far camera: the refusal names the camera ----
sed 's/^camera position 0 1 2.4 /camera position 0 1 1e15 /' scenes/cornell.scene > "$TMP/farcam.scene"
check "control: the far-camera scene moved the camera" grep -q '^camera position 0 1 1e15 ' "$TMP/farcam.scene"
far_camera() {
  expect_exit 2 "the camera lies 1e\+15 from the origin.*eye rays start there" \
    $PM render "$TMP/farcam.scene" "${FAST[@]}" -o "$TMP/far.exr" &&
  ! grep -q "lit part of the scene spans" "$TMP/.stderr" && [ ! -e "$TMP/far.exr" ]
}
check "a camera 1e15 from a room at the origin: refused naming the camera, not the lit part" far_camera

# ---- warnings ----
warns() { # PATTERN SCENE options...: exit 0, stderr matches PATTERN
  local pattern=$1 scene=$2; shift 2
  expect_exit 0 "$pattern" $PM render "$scene" "$@"
}
no_warning() { # SCENE options...: exit 0, no warning
  local scene=$1; shift
  $PM render "$scene" "$@" 2> "$TMP/nw.err" || { echo "exit $?"; cat "$TMP/nw.err"; return 1; }
  ! grep -q warning "$TMP/nw.err" || { cat "$TMP/nw.err"; return 1; }
}
printf 'camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1
material w lambert rho 0.5 0.5 0.5\nrect corner -1 0 -1 edge1 2 0 0 edge2 0 0 2 material w\n' > "$TMP/open.scene"
check "an open scene (a floor only): warns that photons left the scene" \
  warns "warning: [0-9.]+% of the emitted photons .* left the scene" "$TMP/open.scene" "${FAST[@]}" --no-output
printf 'camera position 0 0 0 look_at 0 0 -1 up 0 1 0 fov 60\nlight point position 0 0.5 0 power 1 1 1
material m mirror reflectance 1 1 1\nsphere center 0 0 0 radius 1 material m\n' > "$TMP/mirror.scene"
check "a camera inside a mirror sphere: warns of eye paths cut at the depth limit" \
  warns "warning: [0-9]+ eye paths were cut at the eye-depth limit \(--eye-depth 16\), 100.0%" "$TMP/mirror.scene" \
  "${FAST[@]}" --no-output
printf 'camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1
material w lambert rho 0.5 0.5 0.5\nsphere center 0 1 0 radius 3 material w\nsphere center 0 1 2 radius 0.5 material w\n' \
  > "$TMP/shut.scene"
check "a camera inside a diffuse sphere, the light outside it: warns" \
  warns "warning: the camera \(0 1 2\) is inside the opaque sphere of centre \(0 1 2\) and radius 0.5 \(shape 2" \
  "$TMP/shut.scene" "${FAST[@]}" --no-output
for s in cornell furnace caustic; do
  check "control: scenes/$s.scene (closed; the furnace's camera and light share a sphere) gives no warning" \
    no_warning scenes/$s.scene "${FAST[@]}" --no-output
done

# ---- output names and formats ----
ext_refused() { # OPTION NAME EXT [options]
  local opt=$1 name=$2 ext=$3; shift 3
  rm -rf "$TMP/o"; mkdir -p "$TMP/o"
  expect_exit 2 "^photonmap: $opt: '$TMP/o/$name' does not end in \\$ext" \
    $PM render scenes/cornell.scene "${FAST[@]}" "$@" "$opt" "$TMP/o/$name" && [ -z "$(ls -A "$TMP/o")" ]
}
check "-o x.png: exit 2 naming -o, nothing written" ext_refused -o x.png .exr
check "--png x.exr: exit 2 naming --png" ext_refused --png x.exr .png
check "--stats x.txt: exit 2 naming --stats" ext_refused --stats x.txt .json
check "--dump-reps x.json: exit 2 naming --dump-reps" ext_refused --dump-reps x.json .csv --method precomputed
upper_ok() {
  $PM render scenes/cornell.scene "${FAST[@]}" -o "$TMP/UP.EXR" --png "$TMP/up.PNG" && [ -s "$TMP/UP.EXR" ] && [ -s "$TMP/up.PNG" ]
}
check "extensions in capitals are fine" upper_ok

# ---- a render with no output ----
check "no output option: exit 2 saying what to give" \
  expect_exit 2 "no output: give -o FILE.exr, --png FILE.png, --stats FILE.json or --dump-reps FILE.csv, or --no-output" \
  $PM render scenes/cornell.scene "${FAST[@]}"
timing_only() { # in an empty directory: nothing appears there
  local pm=$PM root=$PWD
  case $pm in /*) ;; *) pm=$root/$pm ;; esac
  rm -rf "$TMP/t"; mkdir -p "$TMP/t"
  (cd "$TMP/t" && "$pm" render "$root/scenes/cornell.scene" --photons 2000 --nn 10 --width 16 --height 12 \
     --no-output 2> "$TMP/t.err") && grep -q "trace .* total " "$TMP/t.err" && [ -z "$(ls -A "$TMP/t")" ]
}
check "--no-output: renders, prints the times, writes no file" timing_only
check "--no-output with -o: exit 2" expect_exit 2 "--no-output contradicts" \
  $PM render scenes/cornell.scene "${FAST[@]}" --no-output -o "$TMP/n.exr"
check "--help lists --no-output" bash -c "$PM render --help | grep -q -- '--no-output'"

# ---- --gather and the direct light ----
check "--gather with --direct photons: exit 2, naming both" \
  expect_exit 2 "--gather .*--direct photons would count it twice" $PM render scenes/cornell.scene "${FAST[@]}" \
  --gather 4 --direct photons --no-output
gather_shadow_rays() {
  $PM render scenes/cornell.scene "${FAST[@]}" --gather 2 --stats "$TMP/g.json" &&
  grep -q '"direct": "shadow-rays"' "$TMP/g.json" &&
  $PM render scenes/cornell.scene "${FAST[@]}" --gather 2 --direct shadow-rays --stats "$TMP/g2.json" &&
  grep -q '"direct": "shadow-rays"' "$TMP/g2.json"
}
check "--gather without --direct, or with --direct shadow-rays: direct light by shadow rays" gather_shadow_rays
check "--gather beyond its range: exit 2" expect_exit 2 "--gather: expected an integer in \[0, 65536\]" \
  $PM render scenes/cornell.scene --gather 70000

finish
