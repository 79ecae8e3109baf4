#!/usr/bin/env bash
# hostile.test.sh: hostile input at the command line. Broken scene
# files give "file:line:col: message", exit 2 and no output file; malformed or
# out-of-range options give a clear message and exit 2; a full disk, an
# unwritable directory or a device as output is an error naming the path, and
# never leaves a partial or temporary file or replaces an existing output.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
trap 'umount "$TMP/full" "$TMP/ro" 2>/dev/null; rm -rf "$TMP"' EXIT

HEAD='camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60
light point position 0 1 0 power 1 1 1
material w lambert rho 1 1 1'
SPHERE='sphere center 0 0 0 radius 1 material w'
FAST=(--photons 500 --nn 5 --width 8 --height 8 --quiet)

# scene_err NAME PATTERN: $TMP/s.scene (already written) fails with exit 2,
# "$TMP/s.scene:LINE:COL: " then PATTERN, and writes none of its outputs
scene_err() {
  local pattern=$1
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  case $pattern in
    :*) pattern="^$TMP/s.scene$pattern" ;;
    *) pattern="^$TMP/s.scene:[0-9]+:[0-9]+: .*$pattern" ;;
  esac
  expect_exit 2 "$pattern" \
    $PM render "$TMP/s.scene" "${FAST[@]}" -o "$TMP/out/a.exr" --png "$TMP/out/a.png" --stats "$TMP/out/a.json" &&
  [ -z "$(ls -A "$TMP/out")" ] || { echo "outputs left:"; ls -A "$TMP/out"; return 1; }
}
# hostile NAME PATTERN TEXT: a scene of TEXT (printf %b) must fail that way
hostile() {
  local name=$1 pattern=$2 text=$3
  printf '%b' "$text" > "$TMP/s.scene"
  check "scene: $name" scene_err "$pattern"
}

hostile "empty file" ":1:1: empty scene: no camera" ""
hostile "only comments and blanks" "no camera" "# nothing\n\n   \n"
printf '%s' "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60
light point position 0 1 0 pow" > "$TMP/s.scene"
check "scene: truncated mid-line (no newline)" scene_err ":2:28: unknown light field 'pow'"
printf '%s' "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60
light point position 0 1" > "$TMP/s.scene"
check "scene: truncated inside a vector" scene_err ":2:25: light field 'position' needs 3 values"
hostile "unknown keyword" ":4:1: unknown keyword 'widget'" "$HEAD\nwidget 1 2 3\n"
hostile "unknown field" "unknown sphere field 'colour'" "$HEAD\nsphere center 0 0 0 radius 1 colour w\n"
hostile "unknown material kind" "unknown material kind 'metal'" "$HEAD\nmaterial m metal rho 1 1 1\n"
hostile "too few values" "expected a number, got 'look_at'" "camera position 0 1 look_at 0 1 0 up 0 1 0 fov 60\n"
hostile "missing value at end of line" "camera field 'fov' needs 1 value" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov\n"
hostile "too many values" "unknown sphere field '4'" "$HEAD\nsphere center 0 0 0 4 radius 1 material w\n"
hostile "missing field" "sphere is missing field 'radius'" "$HEAD\nsphere center 0 0 0 material w\n"
hostile "field given twice" "field 'radius' given twice" "$HEAD\nsphere center 0 0 0 radius 1 radius 2 material w\n"
hostile "NaN coordinate" "number 'nan' is not finite|expected a number, got 'nan'" "$HEAD\nsphere center nan 0 0 radius 1 material w\n"
hostile "NaN power" "expected a number, got 'NaN'|not finite" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power NaN 1 1\n"
hostile "Inf power" "inf|Inf|not finite" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 inf 1\n"
hostile "-Inf radius" "not finite|expected a number" "$HEAD\nsphere center 0 0 0 radius -inf material w\n"
hostile "1e400 radius" "number '1e400' is not finite" "$HEAD\nsphere center 0 0 0 radius 1e400 material w\n"
hostile "1e400 power" "number '1e400' is not finite" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1e400\n"
hostile "negative radius" "out of range" "$HEAD\nsphere center 0 0 0 radius -1 material w\n"
hostile "zero radius" "must be positive" "$HEAD\nsphere center 0 0 0 radius 0 material w\n"
hostile "denormal radius 1e-320" "must be positive and at least 1e-50" "$HEAD\nsphere center 0 0 0 radius 1e-320 material w\n"
hostile "rect edges of 1e-160 (1/|e|^2 overflows)" "edge1 is zero or shorter than 1e-50" "$HEAD\nrect corner 1 0 0 edge1 1e-160 0 0 edge2 0 1e-160 0 material w\n"
hostile "scene of no extent" ":4:1: end of scene: the scene has no extent" "camera position 1 1 1 look_at 1 1 0 up 0 1 0 fov 60\nlight point position 1e15 1e15 1e15 power 1 1 1\nmaterial w lambert rho 1 1 1\nsphere center 1e15 1e15 1e15 radius 1e-40 material w\n"
hostile "negative power" "out of range" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 -1 1\n"
hostile "power above 1e35" "out of range" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1e36 1 1\n"
hostile "coordinate above 1e15" "out of range" "$HEAD\nsphere center 2e15 0 0 radius 1 material w\n"
hostile "hex float" ":4:15: expected a number, got '0x10'" "$HEAD\nsphere center 0x10 0 0 radius 1 material w\n"
hostile "hex float exponent" "expected a number, got '0x1p-3'" "$HEAD\nsphere center 0 0 0 radius 0x1p-3 material w\n"
hostile "rho above 1" "out of range" "$HEAD\nmaterial m lambert rho 1.5 1 1\n"
hostile "fov 180" "out of range" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 180\n"
hostile "look_at equals position" "camera look_at equals its position" "camera position 0 1 0 look_at 0 1 0 up 0 1 0 fov 60\n"
hostile "up parallel to view" "parallel to the view direction" "camera position 0 1 2 look_at 0 1 0 up 0 0 1 fov 60\n"
hostile "duplicate material" ":4:10: material 'w' already defined on line 3" "$HEAD\nmaterial w mirror reflectance 1 1 1\n"
hostile "undefined material" ":4:39: unknown material 'q'" "$HEAD\nsphere center 0 0 0 radius 1 material q\n"
hostile "material used before defined" "unknown material 'w'" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1\n$SPHERE\nmaterial w lambert rho 1 1 1\n"
hostile "bad material name" "bad material name" "$HEAD\nmaterial 9lives lambert rho 1 1 1\n"
hostile "second camera" "second camera" "$HEAD\ncamera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\n"
hostile "second light" "second light" "$HEAD\nlight point position 0 1 0 power 1 1 1\n"
hostile "no camera" "no camera" "light point position 0 1 0 power 1 1 1\nmaterial w lambert rho 1 1 1\n$SPHERE\n"
hostile "no light" "no light" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nmaterial w lambert rho 1 1 1\n$SPHERE\n"
hostile "no shapes" "no shapes" "$HEAD\n"
hostile "non-point light" "expected 'light point" "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight spot position 0 1 0 power 1 1 1\n"
hostile "NUL byte" ":4:7: control byte 0x00" "$HEAD\nsphere\0 center 0 0 0 radius 1 material w\n"
hostile "not UTF-8 in a statement" ":4:8: non-ASCII byte 0xe9" "$HEAD\nsphere \xe9 center\n"
hostile "not UTF-8 in a comment" ":4:6: invalid UTF-8 byte 0xe9 in comment" "$HEAD\n# caf\xe9\n"
hostile "UTF-8 overlong in a comment" "invalid UTF-8 byte 0xc0 in comment" "$HEAD\n# \xc0\xaf\n"
hostile "UTF-16 byte-order mark" ":1:1: non-ASCII byte 0xff" "\xff\xfec\x00a\x00m\x00\n"
hostile "CR-only line ends" "too many fields|unknown camera field" "camera position 0 1 2\rlook_at 0 1 0\rup 0 1 0 fov 60\rlight point\r"

# binary junk: the start of an executable
head -c 4096 "$PM" > "$TMP/s.scene"
check "scene: binary junk (an ELF file)" scene_err "control byte|non-ASCII byte"
# a 10 MB line: one token, then 10 MB of fields
{ printf 'camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60 '; head -c 10000000 /dev/zero | tr '\0' 'x'; echo; } > "$TMP/s.scene"
check "scene: a 10 MB token" scene_err ":1:53: token longer than 256 bytes"
{ printf 'camera'; head -c 10000000 /dev/zero | tr '\0' '\t'; printf 'x'; echo; } > "$TMP/s.scene"
check "scene: a 10 MB line of tabs" scene_err ":1:10000007: unknown camera field 'x'"
{ echo "$HEAD"; printf 'sphere'; for i in $(seq 1 60); do printf ' 1'; done; echo; } > "$TMP/s.scene"
check "scene: too many fields on a line" scene_err ":4:[0-9]+: too many fields on one line"
{ echo "$HEAD"; printf '# '; head -c 10000000 /dev/zero | tr '\0' 'y'; echo; echo "$SPHERE"; } > "$TMP/s.scene"
ok_long_comment() { $PM render "$TMP/s.scene" "${FAST[@]}" -o "$TMP/lc.exr" && [ -s "$TMP/lc.exr" ]; }
check "scene: a 10 MB comment line is fine" ok_long_comment
head -c 70000000 /dev/zero | tr '\0' '#' > "$TMP/s.scene"
check "scene: a 70 MB file is refused" scene_err ":1:1: file larger than 64 MiB"
check "scene: a directory" expect_exit 1 "^$TMP: (read error|cannot open)" $PM render "$TMP" "${FAST[@]}"

# ---- command-line values ----
bad_opt() { # PATTERN, options...: exit 2 with PATTERN, no output
  local pattern=$1; shift
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  expect_exit 2 "$pattern" $PM render scenes/cornell.scene --quiet "$@" -o "$TMP/out/a.exr" &&
  [ -z "$(ls -A "$TMP/out")" ]
}
check "cli: --photons abc" bad_opt "--photons: expected an integer in \[0, 2000000000\], got 'abc'" --photons abc
check "cli: --photons empty" bad_opt "--photons: expected an integer" --photons ""
check "cli: --photons 1e5" bad_opt "--photons: expected an integer" --photons 1e5
check "cli: --photons 0x10" bad_opt "--photons: expected an integer" --photons 0x10
check "cli: --photons '5 '" bad_opt "--photons: expected an integer" --photons "5 "
check "cli: --photons 2000000001" bad_opt "--photons: expected an integer in \[0, 2000000000\]" --photons 2000000001
check "cli: --photons 2^64 overflows" bad_opt "--photons: expected an integer" --photons 18446744073709551616
check "cli: --photons 2e9: refused up front, map too large" bad_opt "--photons 2000000000 would store about .* at most 2\^32-1" --photons 2000000000
check "cli: --nn 100001" bad_opt "--nn: expected an integer in \[2, 100000\]" --nn 100001
check "cli: --height 0" bad_opt "--height: expected an integer in \[1, 16384\]" --height 0
check "cli: 16384x16384 too large" bad_opt "16384x16384 pixels is too large \(at most 67108864 pixels\)" --width 16384 --height 16384
check "cli: --subpixels 17" bad_opt "--subpixels: expected an integer in \[1, 16\]" --subpixels 17
check "cli: --threads 257" bad_opt "--threads: expected an integer in \[0, 256\]" --threads 257
check "cli: --seed -1" bad_opt "--seed: expected an integer" --seed -1
check "cli: --rep-every 0" bad_opt "--rep-every: expected an integer in \[1," --rep-every 0
check "cli: --photon-depth 0" bad_opt "--photon-depth: expected an integer in \[1, 1000\]" --photon-depth 0
check "cli: --eye-depth 1001" bad_opt "--eye-depth: expected an integer in \[0, 1000\]" --eye-depth 1001
check "cli: --max-radius nan" bad_opt "--max-radius: expected a number" --max-radius nan
check "cli: --max-radius inf" bad_opt "--max-radius: expected a number" --max-radius inf
check "cli: --max-radius 0" bad_opt "--max-radius: expected a number in \[1e-30, 1e\+30\]" --max-radius 0
check "cli: --max-radius -1" bad_opt "--max-radius: expected a number" --max-radius -1
check "cli: --normal-cos 1.5" bad_opt "--normal-cos: expected a number in \[-1, 1\]" --normal-cos 1.5
check "cli: --exposure -1" bad_opt "--exposure: expected a number" --exposure -1
check "cli: --direct sideways" bad_opt "--direct: expected photons or shadow-rays" --direct sideways
check "cli: --rep-tree forest" bad_opt "--rep-tree: expected separate or shared" --rep-tree forest
check "cli: two scene files" bad_opt "unexpected argument 'scenes/cornell.scene'" scenes/cornell.scene
check "cli: value missing at the end" expect_exit 2 "--stats needs a value" $PM render scenes/cornell.scene --stats
check "cli: render without a scene" expect_exit 2 "render needs a scene file" $PM render --quiet
check "cli: single-dash unknown flag" bad_opt "unknown option '-x'" -x

photons_zero() { # P_e = 0 is allowed: a black image (documented in --help)
  $PM render scenes/cornell.scene "${FAST[@]}" --photons 0 -o "$TMP/z.exr" --stats "$TMP/z.json" &&
  grep -q '"photons_stored": 0' "$TMP/z.json" && grep -q '"nonfinite_pixels": 0' "$TMP/z.json" && [ -s "$TMP/z.exr" ]
}
check "cli: --photons 0 gives the documented black image" photons_zero

# ---- --rep-count at 0, 1, the stored count and above it ----
rep_count_runs() { # COUNT WANT [options]: renders, its stats count WANT representatives
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  $PM render scenes/cornell.scene "${FAST[@]}" --method precomputed --rep-count "$1" "${@:3}" -o "$TMP/out/a.exr" \
    --stats "$TMP/out/a.json" || { echo "exit $?"; return 1; }
  grep -q "\"representatives\": $2," "$TMP/out/a.json" || { grep representatives "$TMP/out/a.json"; return 1; }
}
$PM render scenes/cornell.scene "${FAST[@]}" --method precomputed --stats "$TMP/rc0.json"
STORED=$(sed -n 's/.*"photons_stored": \([0-9]*\),/\1/p' "$TMP/rc0.json")
EVERY4=$(sed -n 's/.*"representatives": \([0-9]*\),/\1/p' "$TMP/rc0.json")
check "--rep-count: the pilot stored photons ($STORED)" test "${STORED:-0}" -gt 10
check "--rep-count 0: the --rep-every rule ($EVERY4)" rep_count_runs 0 "$EVERY4"
check "--rep-count 1: one representative" rep_count_runs 1 1
check "--rep-count at the stored count: every stored photon" rep_count_runs "$STORED" "$STORED"
check "--rep-count above the stored count: every stored photon" rep_count_runs $((STORED + 1)) "$STORED"
check "--rep-count 4294967295 (the top of its range): every stored photon" rep_count_runs 4294967295 "$STORED"
check "--rep-count 4294967296: exit 2" bad_opt "--rep-count: expected an integer in \[0, 4294967295\]" \
  --method precomputed --rep-count 4294967296
rep_count_corrected() { # COUNT: refused with --bias-correction, naming both, nothing written
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  expect_exit 2 "--rep-count $1 flags every one of the $STORED stored photons, and --bias-correction" \
    $PM render scenes/cornell.scene "${FAST[@]}" --method precomputed --bias-correction --rep-count "$1" \
    -o "$TMP/out/a.exr" --stats "$TMP/out/a.json" --dump-reps "$TMP/out/a.csv" && [ -z "$(ls -A "$TMP/out")" ]
}
check "--rep-count at the stored count, --bias-correction: exit 2, nothing written" rep_count_corrected "$STORED"
check "--rep-count above the stored count, --bias-correction: exit 2, nothing written" rep_count_corrected $((STORED + 1))
check "--rep-count 1, --bias-correction: renders" rep_count_runs 1 1 --bias-correction

# ---- --dump-reps to paths it cannot write ----
dump_err() { # CODE PATTERN PATH [options]: fails so, before rendering, and writes none of the outputs
  local code=$1 pattern=$2 path=$3; shift 3
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  expect_exit "$code" "$pattern" timeout 60 $PM render scenes/cornell.scene "${FAST[@]}" --method precomputed "$@" \
    -o "$TMP/out/a.exr" --stats "$TMP/out/a.json" --dump-reps "$path" &&
  [ -z "$(ls -A "$TMP/out")" ] || { echo "outputs left:"; ls -A "$TMP/out"; return 1; }
}
check "--dump-reps into a missing directory: exit 1 naming it" dump_err 1 "^photonmap: /nonexistent-dir/r.csv: cannot write" /nonexistent-dir/r.csv
echo x > "$TMP/plain-r"
check "--dump-reps under a regular file: exit 1 naming it" dump_err 1 "^photonmap: $TMP/plain-r/r.csv: cannot write" "$TMP/plain-r/r.csv"
mkdir -p "$TMP/rdir.csv"
check "--dump-reps to a directory: exit 1" dump_err 1 "^photonmap: $TMP/rdir.csv: not a regular file" "$TMP/rdir.csv"
mkfifo "$TMP/fifo.csv"
check "--dump-reps to a FIFO: exit 1 at once, no hang" dump_err 1 "^photonmap: $TMP/fifo.csv: not a regular file" "$TMP/fifo.csv"
check "control: the FIFO is still a FIFO" test -p "$TMP/fifo.csv"
ln -sf /dev/full "$TMP/full.csv"
check "--dump-reps to /dev/full (a link): exit 1, /dev/full untouched" dump_err 1 "^photonmap: $TMP/full.csv: not a regular file" "$TMP/full.csv"
: > "$TMP/out-same.exr"; ln -sf out-same.exr "$TMP/same-reps.csv"
same_as_exr() {
  rm -rf "$TMP/out"; mkdir -p "$TMP/out"
  expect_exit 2 "-o and --dump-reps name the same file" $PM render scenes/cornell.scene "${FAST[@]}" --method precomputed \
    -o "$TMP/out-same.exr" --stats "$TMP/out/a.json" --dump-reps "$TMP/same-reps.csv" &&
  [ ! -s "$TMP/out-same.exr" ] && [ -z "$(ls -A "$TMP/out")" ]
}
check "--dump-reps the same file as -o (a link): exit 2, nothing written" same_as_exr
echo old > "$TMP/st.json"; ln -sf st.json "$TMP/st.csv"
same_as_stats() {
  expect_exit 2 "--stats and --dump-reps name the same file" $PM render scenes/cornell.scene "${FAST[@]}" \
    --method precomputed --stats "$TMP/st.json" --dump-reps "$TMP/st.csv" && [ "$(cat "$TMP/st.json")" = old ]
}
check "--dump-reps the same file as --stats (a link): exit 2, the old file kept" same_as_stats
check "--dump-reps without .csv: exit 2 naming --dump-reps" dump_err 2 "^photonmap: --dump-reps: '$TMP/r.txt' does not end in .csv" "$TMP/r.txt"

# ---- the BVH (from 24 shapes) with degenerate shapes ----
ROOM='camera position 0 1 2.4 look_at 0 1 0 up 0 1 0 fov 65
light point position 0 1.75 0 power 12.566371 12.566371 12.566371
material w lambert rho 0.75 0.75 0.75
sphere center 0 1 0 radius 3 material w'
bvh_ok() { # the scene $TMP/s.scene renders, by the BVH the same image as by the loop over the shapes
  rm -f "$TMP/bvh.exr" "$TMP/lin.exr"
  $PM render "$TMP/s.scene" "${FAST[@]}" --accel bvh -o "$TMP/bvh.exr" --stats "$TMP/bvh.json" || { echo "exit $?"; return 1; }
  grep -q '"nonfinite_pixels": 0' "$TMP/bvh.json" && ! grep -q '"mean_radiance": \[0, 0, 0\]' "$TMP/bvh.json" &&
  { [ "${1:-}" = nolinear ] || { $PM render "$TMP/s.scene" "${FAST[@]}" --accel linear -o "$TMP/lin.exr" && cmp "$TMP/bvh.exr" "$TMP/lin.exr"; }; }
}
{ echo "$ROOM"; for i in $(seq 10 49); do echo "rect corner 0.$i 1 0 edge1 1e-50 0 0 edge2 0 0 1e-50 material w"; done; } > "$TMP/s.scene"
check "BVH: 40 rectangles with edges of 1e-50 (the shortest accepted) render, as by the loop" bvh_ok
{ echo "$ROOM"; for i in $(seq 10 49); do echo "rect corner 0.$i 1 0 edge1 1e-50 0 0 edge2 0 0 1 material w"; done; } > "$TMP/s.scene"
check "BVH: 40 slivers of 1e-50 x 1 render, as by the loop" bvh_ok
{ echo "$ROOM"; for i in $(seq 10 49); do echo "sphere center 0.$i 1 0 radius 1e-50 material w"; done; } > "$TMP/s.scene"
check "BVH: 40 spheres of radius 1e-50 render, as by the loop" bvh_ok
{ echo "$ROOM"; for i in $(seq 10 49); do echo "sphere center 0 1 0 radius 1e-50 material w"; done; } > "$TMP/s.scene"
check "BVH: 40 coincident spheres of radius 1e-50 render, as by the loop" bvh_ok
{ echo "$ROOM"; for i in $(seq 1 30); do echo "rect corner 0 1 0 edge1 1e-49 0 0 edge2 0 1e-49 0 material w"; done
  echo "rect corner 0 1 0 edge1 1e-51 0 0 edge2 0 1 0 material w"; } > "$TMP/s.scene"
check "BVH scene: a rectangle edge of 1e-51 (below the limit) is refused at its line" scene_err ":35:[0-9]+: rect edge1 is zero or shorter than 1e-50"
{ echo "$ROOM"; for i in $(seq 1 30); do echo "sphere center 0 1 0 radius 1e-50 material w"; done
  echo "sphere center 0 1 0 radius 9e-51 material w"; } > "$TMP/s.scene"
check "BVH scene: a sphere of radius 9e-51 is refused at its line" scene_err ":35:[0-9]+: sphere radius must be positive and at least 1e-50"
{ echo "$ROOM"; for i in $(seq 1 30); do echo "rect corner 0 1 0 edge1 1 0 0 edge2 1 1e-20 0 material w"; done; } > "$TMP/s.scene"
check "BVH scene: a zero-area rectangle (parallel edges) is refused at its line" scene_err ":5:[0-9]+: rect edges are not perpendicular"
# 100,000 shapes (the most a scene may hold), 99,999 of them at one place
{ echo "$ROOM"; awk 'BEGIN { for (i = 0; i < 99999; i++) print "sphere center 0 0.5 0 radius 0.2 material w" }'; } > "$TMP/s.scene"
check "BVH: 99,999 coincident spheres and a room (100,000 shapes) render" bvh_ok nolinear
{ echo "$ROOM"; awk 'BEGIN { for (i = 0; i < 99999; i++) print "rect corner -0.5 0.5 -0.5 edge1 1 0 0 edge2 0 0 1 material w" }'; } > "$TMP/s.scene"
check "BVH: 99,999 coincident rectangles and a room render" bvh_ok nolinear
echo "sphere center 0 0.5 0 radius 0.2 material w" >> "$TMP/s.scene"
check "scene: 100,001 shapes are refused at the one too many" scene_err ":100004:1: too many shapes \(at most 100000\)"

# ---- outputs ----
# a device through a link of the right extension (a name without it is
# refused for its extension first)
for dev in /dev/full /dev/null; do
  ln -sf "$dev" "$TMP/dev-$(basename $dev).exr"
  check "output: $dev is refused, not replaced" \
    bash -c "rc=0; $PM render scenes/cornell.scene ${FAST[*]} -o $TMP/dev-$(basename $dev).exr 2>$TMP/dev.err || rc=\$?; [ \$rc -eq 1 ] && grep -q '^photonmap: $TMP/dev-$(basename $dev).exr: not a regular file' $TMP/dev.err && [ -c $dev ]"
done
mkdir -p "$TMP/dir.exr"
check "output: a directory as output is refused up front" expect_exit 1 "^photonmap: $TMP/dir.exr: not a regular file" $PM render scenes/cornell.scene "${FAST[@]}" -o "$TMP/dir.exr"
echo x > "$TMP/plain"
check "output: a path under a regular file" expect_exit 1 "^photonmap: $TMP/plain/a.exr: cannot write" $PM render scenes/cornell.scene "${FAST[@]}" -o "$TMP/plain/a.exr"

# full disk: a 64 KiB tmpfs (needs root and mount; skipped with a note otherwise)
mkdir -p "$TMP/full"
if mount -t tmpfs -o size=64k tmpfs "$TMP/full" 2>/dev/null; then
  full_disk() {
    echo old > "$TMP/full/a.exr"
    expect_exit 1 "^photonmap: $TMP/full/(a.exr|a.png): .*(write|Write)" \
      $PM render scenes/cornell.scene --photons 2000 --nn 10 --width 256 --height 192 --quiet \
      -o "$TMP/full/a.exr" --png "$TMP/full/a.png" &&
    [ "$(cat "$TMP/full/a.exr")" = old ] && [ ! -e "$TMP/full/a.png" ] &&
    [ -z "$(ls "$TMP/full" | grep '\.tmp\.')" ]
  }
  check "output: full disk names the path, keeps the old file, leaves no temporary" full_disk
  umount "$TMP/full"
else
  skip "output: full disk (cannot mount a tmpfs here)"
fi
# unwritable directory: a read-only tmpfs as root (root ignores modes), chmod otherwise
mkdir -p "$TMP/ro"
if [ "$(id -u)" -ne 0 ]; then
  chmod 555 "$TMP/ro"
  check "output: unwritable directory names the path" expect_exit 1 "^photonmap: $TMP/ro/a.exr: cannot write: Permission denied" $PM render scenes/cornell.scene "${FAST[@]}" -o "$TMP/ro/a.exr"
elif mount -t tmpfs -o size=64k,ro tmpfs "$TMP/ro" 2>/dev/null; then
  check "output: read-only directory names the path" expect_exit 1 "^photonmap: $TMP/ro/a.exr: cannot write: Read-only file system" $PM render scenes/cornell.scene "${FAST[@]}" -o "$TMP/ro/a.exr"
  umount "$TMP/ro"
else
  skip "output: unwritable directory (root and no read-only mount)"
fi

finish
