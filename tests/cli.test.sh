#!/usr/bin/env bash
# cli.test.sh: the command line as users and scripts see it: outputs, stats
# keys, exit codes and messages, atomic outputs, determinism across threads.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

SMALL=(--photons 20000 --nn 20 --width 64 --height 48 --quiet)

render_ok() {
  $PM render scenes/cornell.scene "${SMALL[@]}" -o "$TMP/a.exr" --png "$TMP/a.png" --stats "$TMP/a.json" &&
  [ -s "$TMP/a.exr" ] && [ -s "$TMP/a.png" ] && [ -s "$TMP/a.json" ] &&
  ! ls "$TMP"/*.tmp.* 2>/dev/null
}
check "render writes exr, png and stats" render_ok

stats_keys() {
  for k in method photons_emitted photons_stored nn width height samples_per_pixel threads seed \
           time_s trace build render total nonfinite_pixels representatives precompute; do
    grep -q "\"$k\"" "$TMP/a.json" || { echo "missing key $k"; return 1; }
  done
  grep -q '"samples_per_pixel": 4' "$TMP/a.json" && grep -q '"photons_emitted": 20000' "$TMP/a.json"
}
check "stats has the documented keys" stats_keys

threads_identical() {
  $PM render scenes/cornell.scene "${SMALL[@]}" --threads 1 -o "$TMP/t1.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --threads 2 -o "$TMP/t2.exr" &&
  cmp "$TMP/t1.exr" "$TMP/t2.exr"
}
check "exr bit-identical for 1 and 2 threads" threads_identical

# --gather: both methods, 1 and 2 threads, the same image bit for bit; the
# stats name the gather's counters and the caustic map, and both methods
# cast the same rays (only the estimate at the gather hits differs)
GATHER=(--gather 6 --photons 10000 --nn 20 --width 32 --height 24 --quiet)
gather_threads_identical() {
  local m
  for m in conventional precomputed; do
    $PM render scenes/cornell.scene "${GATHER[@]}" --method $m --threads 1 -o "$TMP/g1.exr" --stats "$TMP/g-$m.json" &&
    $PM render scenes/cornell.scene "${GATHER[@]}" --method $m --threads 2 -o "$TMP/g2.exr" &&
    cmp "$TMP/g1.exr" "$TMP/g2.exr" || { echo "$m: 1 and 2 threads differ"; return 1; }
  done
  for k in gather gather_work gather_time caustic_photons bytes_caustic_map; do
    grep -q "\"$k\"" "$TMP/g-conventional.json" || { echo "missing key $k"; return 1; }
  done
  grep -q '"direct": "shadow-rays"' "$TMP/g-conventional.json" && grep -q '"gather": 6,' "$TMP/g-conventional.json" &&
  grep -Eq '"caustic_photons": [1-9]' "$TMP/g-conventional.json" || { echo "direct, gather or caustic map"; return 1; }
  local a b
  a=$(grep -o '"gather_work": {"rays": [0-9]*, "specular": [0-9]*, "lookups": [0-9]*' "$TMP/g-conventional.json")
  b=$(grep -o '"gather_work": {"rays": [0-9]*, "specular": [0-9]*, "lookups": [0-9]*' "$TMP/g-precomputed.json")
  [ -n "$a" ] && [ "$a" = "$b" ] || { echo "the methods' rays differ: $a / $b"; return 1; }
}
check "--gather: exr bit-identical for 1 and 2 threads, both methods; the same gather rays; stats keys" \
  gather_threads_identical
gather_zero_unchanged() {
  $PM render scenes/cornell.scene "${SMALL[@]}" -o "$TMP/g0.exr" --gather 0 && cmp "$TMP/a.exr" "$TMP/g0.exr"
}
check "--gather 0: the image without --gather, bit for bit" gather_zero_unchanged

precomputed_ok() {
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --stats "$TMP/p.json" &&
  grep -q '"method": "precomputed"' "$TMP/p.json" && grep -qE '"representatives": [1-9]' "$TMP/p.json"
}
check "precomputed method runs and reports representatives" precomputed_ok

check "no arguments: usage, exit 2" expect_exit 2 "usage" $PM

# --dump-reps: one CSV line per representative (as many as the stats count),
# in both layouts; the image and its times do not depend on it
dump_reps() { # extra options...
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --threads 1 "$@" --dump-reps "$TMP/reps.csv" \
      --stats "$TMP/d.json" -o "$TMP/d.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --threads 1 "$@" -o "$TMP/nd.exr" &&
  cmp "$TMP/d.exr" "$TMP/nd.exr" && head -n 1 "$TMP/reps.csv" | grep -qx 'x,y,z,nx,ny,nz,e_r,e_g,e_b' &&
  reps=$(sed -n 's/.*"representatives": \([0-9]*\),/\1/p' "$TMP/d.json") &&
  [ "$reps" -gt 0 ] && [ "$(($(wc -l < "$TMP/reps.csv") - 1))" -eq "$reps" ] &&
  awk -F, 'NR > 1 && (NF != 9 || $2 < -0.001 || $2 > 2.001 || $7 < 0) { bad = 1 } END { exit bad }' "$TMP/reps.csv" &&
  ! ls "$TMP"/*.tmp.* 2>/dev/null
}
check "--dump-reps: a CSV line per representative, image unchanged" dump_reps
check "--dump-reps with --rep-tree shared" dump_reps --rep-tree shared
check "--dump-reps without --method precomputed: exit 2" \
  expect_exit 2 "--dump-reps writes the representatives of the precomputed method" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --dump-reps "$TMP/x.csv"
check "--dump-reps to an unwritable path: exit 1 before rendering" \
  expect_exit 1 "/nonexistent-dir/reps.csv: cannot write" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --dump-reps /nonexistent-dir/reps.csv
# one file under two names of the right extensions: a link
: > "$TMP/same.exr"; ln -sf same.exr "$TMP/same.csv"
check "--dump-reps and -o on one file (a link): exit 2" expect_exit 2 "name the same file" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed -o "$TMP/same.exr" --dump-reps "$TMP/same.csv"

# --rep-count: the fixed-count rule, reported in the stats
rep_count_ok() {
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --rep-count 1234 --stats "$TMP/c.json" &&
  grep -q '"representatives": 1234,' "$TMP/c.json" && grep -q '"rep_count": 1234,' "$TMP/c.json"
}
check "--rep-count N: N representatives" rep_count_ok
check "--rep-count with --rep-every: exit 2" expect_exit 2 "--rep-count and --rep-every are two rules" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --rep-count 100 --rep-every 2
check "--rep-count with --rep-every at its default value: exit 2, naming both" expect_exit 2 "--rep-count and --rep-every are two rules" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --rep-count 10 --rep-every 4
check "--rep-count at or above the stored photons with --bias-correction: exit 2 naming both" \
  expect_exit 2 "--rep-count 10000000 flags every one of the [0-9]+ stored photons" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --rep-count 10000000 --bias-correction --no-output

# --help of each subcommand: exit 0, every option with its default (and its
# range for numbers), from the one option table that also parses
help_lists() { # subcommand, options...
  local sub=$1; shift
  $PM "$sub" --help > "$TMP/help.txt" || { echo "exit $?"; return 1; }
  for o in "$@"; do
    grep -A1 -E "^  $o( |\$)" "$TMP/help.txt" | grep -q "(default: " || { echo "$o missing or without a default"; return 1; }
  done
  # every option block has a default; every numeric one a range
  local blocks defaults
  blocks=$(grep -cE '^  -' "$TMP/help.txt"); defaults=$(grep -c '(default: ' "$TMP/help.txt")
  [ "$blocks" -eq $((defaults + 1)) ] || { echo "$blocks options, $defaults defaults"; return 1; }
  ! grep -E '^      .*\(default: [0-9.e+-]+\)$' "$TMP/help.txt" | grep -v -- '--exposure' | grep -q . ||
    { echo "a number without its range:"; grep -E '\(default: [0-9.e+-]+\)$' "$TMP/help.txt"; return 1; }
}
check "render --help: exit 0, every option with default and range" help_lists render --method --photons --nn --width \
  --height --subpixels --threads --seed --rep-every --rep-count --normal-cos --rep-tree --max-radius --direct \
  --photon-depth --eye-depth --gather -o --png --exposure --stats --dump-reps --allow-nonfinite --quiet
check "export-pov --help: exit 0, every option with default and range" help_lists export-pov --width --height \
  --quality --no-radiosity --no-photons --no-glass-caustics -o
check "photonmap --help: both subcommands, exit 0" bash -c "$PM --help | grep -q 'usage: photonmap render' && $PM --help | grep -q 'usage: photonmap export-pov'"
check "export-pov: malformed option, same message style as render, exit 2" \
  expect_exit 2 "^photonmap: --width: expected an integer in \[1, 16384\], got 'wide'" $PM export-pov scenes/cornell.scene --width wide
check "unknown command: exit 2" expect_exit 2 "unknown command 'draw'" $PM draw
check "--nn 0: exit 2" expect_exit 2 "--nn: expected an integer in \[2," $PM render scenes/cornell.scene --nn 0
check "--photons -5: exit 2" expect_exit 2 "--photons: expected an integer" $PM render scenes/cornell.scene --photons -5
check "--width 1e9: exit 2" expect_exit 2 "--width: expected an integer" $PM render scenes/cornell.scene --width 1e9
check "--width 99999: exit 2" expect_exit 2 "--width: expected an integer in \[1, 16384\]" $PM render scenes/cornell.scene --width 99999
check "unknown flag: exit 2" expect_exit 2 "unknown option '--fast'" $PM render scenes/cornell.scene --fast
check "flag without value: exit 2" expect_exit 2 "--nn needs a value" $PM render scenes/cornell.scene --nn
check "bad method: exit 2" expect_exit 2 "--method: expected conventional or precomputed" $PM render scenes/cornell.scene --method fast
check "bad --accel: exit 2" expect_exit 2 "--accel: expected auto, bvh or linear" $PM render scenes/cornell.scene --accel kd
accel_identical() { # the BVH and the loop over every shape give the same image
  $PM render scenes/cornell.scene "${SMALL[@]}" --accel bvh -o "$TMP/bvh.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --accel linear -o "$TMP/lin.exr" &&
  cmp "$TMP/bvh.exr" "$TMP/lin.exr"
}
check "exr bit-identical with --accel bvh and linear" accel_identical
check "export-pov: --rect-thickness out of range: exit 2" expect_exit 2 "--rect-thickness: expected a number in \[1e-09, 0.01\]" \
  $PM export-pov scenes/cornell.scene --rect-thickness 0.1
check "export-pov: --bounces 0: exit 2" expect_exit 2 "--bounces: expected an integer in \[1, 20\]" $PM export-pov scenes/cornell.scene --bounces 0

# --no-glass-caustics: the glass is no photon target and gets its shadow-only
# proxy; the mirror stays a target; the committed negative-control references
# were exported this way (negative control: the plain export is not that)
no_glass_caustics() {
  $PM export-pov scenes/cornell.scene --width 256 --height 192 --quality fast --no-glass-caustics > "$TMP/nc.pov" &&
  $PM export-pov scenes/cornell.scene --width 256 --height 192 --quality fast > "$TMP/c.pov" &&
  ! grep -q 'photons { target reflection on refraction on' "$TMP/nc.pov" &&
  grep -q 'photons { target reflection on refraction on' "$TMP/c.pov" &&
  grep -q 'photons { target reflection on refraction off' "$TMP/nc.pov" &&
  grep -q 'shadow-only proxy' "$TMP/nc.pov" && ! grep -q 'shadow-only proxy' "$TMP/c.pov" &&
  cmp -s "$TMP/nc.pov" reference/cornell/cornell-nocaustic-128x96.pov && ! cmp -s "$TMP/c.pov" reference/cornell/cornell-nocaustic-128x96.pov
}
check "export-pov --no-glass-caustics: no glass target, its proxy, the committed negative control" no_glass_caustics
check "missing scene file: exit 1 naming it" expect_exit 1 "nope.scene: cannot open" $PM render nope.scene

bad_scene() {
  printf 'camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1\nmaterial white lambert rho 1 1 1\nsphere center 0 0 0 radius 1 material whte\n' > "$TMP/x.scene"
  expect_exit 2 "^$TMP/x.scene:4:39: unknown material 'whte'" $PM render "$TMP/x.scene" -o "$TMP/x.exr" &&
  [ ! -e "$TMP/x.exr" ]
}
check "scene error: file:line:col, exit 2, no output" bad_scene

unwritable() {
  expect_exit 1 "/nonexistent-dir/out.exr: cannot write" $PM render scenes/cornell.scene "${SMALL[@]}" -o /nonexistent-dir/out.exr
}
check "unwritable output: exit 1 naming the path, before rendering" unwritable

killed_keeps_old() {
  echo "old" > "$TMP/keep.exr"
  $PM render scenes/cornell.scene --photons 200000 --nn 100 --width 512 --height 384 --threads 1 --quiet \
      -o "$TMP/keep.exr" &
  local pid=$!
  sleep 1
  kill -9 "$pid"; wait "$pid" 2>/dev/null
  [ "$(cat "$TMP/keep.exr")" = "old" ]
}
check "a killed run leaves an existing output untouched" killed_keeps_old

# --repeats: the same image as one render, every repeat's times, minima;
# the work counters the same for 1 and 2 threads; provenance in the stats
repeats_ok() {
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --threads 1 -o "$TMP/r1.exr" \
      --stats "$TMP/r1.json" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --method precomputed --threads 2 --repeats 3 -o "$TMP/r3.exr" \
      --stats "$TMP/r3.json" &&
  cmp "$TMP/r1.exr" "$TMP/r3.exr" &&
  "${PYTHON:-/usr/bin/python3}" - "$TMP/r1.json" "$TMP/r3.json" <<'PY'
import json, sys
one, three = (json.load(open(f)) for f in sys.argv[1:])
assert one["repeats"] == 1 and three["repeats"] == 3, (one["repeats"], three["repeats"])
reps = three["time_s_repeats"]
for k in ("trace", "build", "precompute", "render", "total"):
    assert len(reps[k]) == 3 and three["time_s"][k] == min(reps[k]), k
    assert three["time_s_cold"][k] == reps[k][0] and three["time_s_median"][k] == sorted(reps[k])[1], k
assert one["work"] == three["work"], "work differs between 1 thread and 2 threads x 3 repeats"
assert three["work"]["render"]["rep_lookups"] > 0 and three["work"]["precompute"]["knn_queries"] > 0
p = three["provenance"]
assert set(p) == {"commit", "tree", "compiler", "flags", "cpu", "threads", "loadavg"} and p["threads"] == 2, p
# kept memory: a warm repeat touches next to no fresh page (with malloc's
# heap holding the mid-size buffers the second repeat faulted 90% as many);
# under ASan, whose allocator holds freed memory back, only the counts' shape
faults = three["minor_faults_repeats"]
assert len(faults) == 3 and len(one["minor_faults_repeats"]) == 1, (faults, one["minor_faults_repeats"])
if "-fsanitize=address" not in p["flags"]:
    assert faults[0] > 0 and max(faults[1:]) <= 0.1 * faults[0], faults
PY
}
check "--repeats 3: the same image, each repeat's times, minima, median, cold, page faults; work as on 1 thread" repeats_ok
check "--repeats 0: exit 2" expect_exit 2 "expected auto or a count from 1 to 100" \
  $PM render scenes/cornell.scene "${SMALL[@]}" --repeats 0 --no-output
check "--repeats auto: at least 3 repeats" bash -c \
  "$PM render scenes/cornell.scene --photons 2000 --width 16 --height 12 --quiet --repeats auto --stats $TMP/ra.json &&
   grep -qE '\"repeats\": ([3-9]|10),' $TMP/ra.json"

finish
