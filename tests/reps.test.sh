#!/usr/bin/env bash
# reps.test.sh: the precomputed method's variants beyond the paper, as the
# command line gives them: --rep-eval lazy renders the eager image bit for
# bit (1 and 2 threads, both layouts, with the gate, with --bias-correction)
# and computes fewer representatives; --rep-gate plane and plane-lookup
# change nothing where no representative fails them (the furnace sphere,
# even with kNN radii far above its curvature's 2 tau R) and fall back where
# one must (thin slabs); each is refused where it cannot apply, with the
# reason.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

SMALL=(--photons 20000 --nn 20 --width 64 --height 48 --quiet --method precomputed)

stat() { # file key: the integer value of key
  sed -n "s/.*\"$2\": \([0-9]*\),*/\1/p" "$1"
}

lazy_identical() { # extra options...
  $PM render scenes/cornell.scene "${SMALL[@]}" --threads 1 "$@" -o "$TMP/e.exr" --stats "$TMP/e.json" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --threads 1 "$@" --rep-eval lazy -o "$TMP/l1.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --threads 2 "$@" --rep-eval lazy -o "$TMP/l2.exr" \
      --stats "$TMP/l.json" &&
  cmp "$TMP/e.exr" "$TMP/l1.exr" && cmp "$TMP/e.exr" "$TMP/l2.exr" &&
  local n e l
  n=$(stat "$TMP/e.json" representatives); e=$(stat "$TMP/e.json" reps_evaluated)
  l=$(stat "$TMP/l.json" reps_evaluated)
  grep -q '"rep_eval": "lazy"' "$TMP/l.json" && [ "$e" -eq "$n" ] && [ "$l" -gt 0 ] && [ "$l" -lt "$n" ] ||
    { echo "representatives $n, evaluated eager $e, lazy $l"; return 1; }
}
check "--rep-eval lazy: the eager image bit for bit (1 and 2 threads), fewer evaluated" lazy_identical
check "--rep-eval lazy with --rep-tree shared" lazy_identical --rep-tree shared
check "--rep-eval lazy with --bias-correction" lazy_identical --bias-correction
check "--rep-eval lazy with --rep-gate plane" lazy_identical --rep-gate plane
check "--rep-eval lazy with --rep-gate plane-lookup" lazy_identical --rep-gate plane-lookup
# negative control: the comparison sees a change of the representatives
lazy_control() {
  $PM render scenes/cornell.scene "${SMALL[@]}" -o "$TMP/e.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --rep-eval lazy --rep-every 5 -o "$TMP/l.exr" &&
  ! cmp -s "$TMP/e.exr" "$TMP/l.exr"
}
check "negative control: lazy with other representatives differs" lazy_control

# The furnace sphere (radius 1): the gate's height of two points of one
# sphere is 0 (est_surface_height), so every representative and photon in
# range passes
FURNACE=(scenes/furnace.scene --photons 100000 --nn 100 --width 96 --height 72 --quiet --method precomputed)
gate_unchanged() { # gate, extra options...
  local gate=$1; shift
  $PM render "${FURNACE[@]}" "$@" -o "$TMP/n.exr" &&
  $PM render "${FURNACE[@]}" "$@" --rep-gate "$gate" -o "$TMP/g.exr" --stats "$TMP/g.json" &&
  cmp "$TMP/n.exr" "$TMP/g.exr" && [ "$(stat "$TMP/g.json" rep_fallbacks)" -eq 0 ] &&
  grep -q "\"rep_gate\": \"$gate\"" "$TMP/g.json"
}
check "--rep-gate plane on the furnace sphere: the same image, no fallback" gate_unchanged plane
check "--rep-gate plane on the furnace sphere with --bias-correction: the same image" gate_unchanged plane --bias-correction
check "--rep-gate plane-lookup on the furnace sphere: the same image, no fallback" gate_unchanged plane-lookup
# kNN radii of about 0.3 (1000 photons of 40,000 on the unit sphere): a
# point 0.3 away lies 0.045 from the tangent plane, above tau r = 0.03, so
# a test against the tangent plane alone would fail them; this one sees
# one surface
FURNACE=(scenes/furnace.scene --photons 20000 --nn 1000 --max-radius 0.8 --width 48 --height 36 --quiet
         --method precomputed)
check "--rep-gate plane, kNN radii far above 2 tau R on the sphere: the same image" gate_unchanged plane
# where surfaces lie closer than a kNN radius (thin slabs, their corners),
# some eye samples find no representative that passes: they fall back
gate_falls_back() { # gate
  $PM render scenes/slabs.scene --photons 50000 --width 64 --height 48 --quiet --method precomputed \
      --rep-gate "$1" --stats "$TMP/s.json" -o "$TMP/s.exr" &&
  $PM render scenes/slabs.scene --photons 50000 --width 64 --height 48 --quiet --method precomputed -o "$TMP/p.exr" &&
  [ "$(stat "$TMP/s.json" rep_fallbacks)" -gt 0 ] && ! cmp -s "$TMP/s.exr" "$TMP/p.exr"
}
check "--rep-gate plane among thin slabs: rep_fallbacks > 0, another image" gate_falls_back plane
check "--rep-gate plane-lookup among thin slabs: rep_fallbacks > 0, another image" gate_falls_back plane-lookup

check "render --help lists the variants with default and range" bash -c \
  "$PM render --help | grep -A1 -E '^  --rep-eval eager\|lazy' | grep -q '(default: eager)' &&
   $PM render --help | grep -A1 -E '^  --rep-gate none\|plane\|plane-lookup' | grep -q '(default: none)' &&
   $PM render --help | grep -A1 -E '^  --rep-gate-tau T' | grep -q '(default: 0.1; a number in \[0.001, 1\])'"

# refused where they cannot apply, with the reason
C=(scenes/cornell.scene --photons 1000 --width 8 --height 8 --quiet)
check "--rep-eval lazy with the conventional method: exit 2" \
  expect_exit 2 "--rep-eval lazy evaluates the representatives of the precomputed method" $PM render "${C[@]}" --rep-eval lazy
check "--rep-gate plane with the conventional method: exit 2" \
  expect_exit 2 "--rep-gate plane \(and plane-lookup\) chooses among the representatives" \
  $PM render "${C[@]}" --rep-gate plane
check "--rep-gate plane-lookup with the conventional method: exit 2" \
  expect_exit 2 "chooses among the representatives" $PM render "${C[@]}" --rep-gate plane-lookup
check "--rep-gate-tau without --rep-gate plane: exit 2" \
  expect_exit 2 "--rep-gate-tau is the plane gate's tolerance" $PM render "${C[@]}" --method precomputed --rep-gate-tau 0.2
check "--rep-gate plane with --rep-tree shared: exit 2" \
  expect_exit 2 "--rep-tree shared has none" $PM render "${C[@]}" --method precomputed --rep-gate plane --rep-tree shared
check "--rep-gate plane-lookup with --rep-tree shared: exit 2" expect_exit 2 "--rep-tree shared has none" \
  $PM render "${C[@]}" --method precomputed --rep-gate plane-lookup --rep-tree shared
check "--rep-eval lazy with --dump-reps: exit 2" \
  expect_exit 2 "--rep-eval lazy computes only those the eye pass selects" \
  $PM render "${C[@]}" --method precomputed --rep-eval lazy --dump-reps "$TMP/r.csv"
check "--rep-gate-tau 0: exit 2 with its range" \
  expect_exit 2 "--rep-gate-tau: expected a number in \[0.001, 1\]" $PM render "${C[@]}" --rep-gate plane --rep-gate-tau 0
check "--rep-eval bogus: exit 2" expect_exit 2 "--rep-eval: expected eager or lazy" $PM render "${C[@]}" --rep-eval bogus
# negative control: the accepted combinations run
check "--rep-gate plane --rep-gate-tau 0.2 --rep-eval lazy --bias-correction runs" \
  $PM render "${C[@]}" --method precomputed --rep-gate plane --rep-gate-tau 0.2 --rep-eval lazy --bias-correction \
  -o "$TMP/ok.exr"

finish
