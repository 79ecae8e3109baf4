#!/usr/bin/env bash
# reps.test.sh: the precomputed method's variants beyond the paper, as the
# command line gives them: --rep-eval lazy renders the eager image bit for
# bit (1 and 2 threads, both layouts, with the gate, with --bias-correction)
# and computes fewer representatives; --rep-gate plane changes nothing where
# no representative fails it (the furnace sphere at the default tau) and
# falls back where one must (thin slabs); each is refused where it cannot
# apply, with the reason.
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
# negative control: the comparison sees a change of the representatives
lazy_control() {
  $PM render scenes/cornell.scene "${SMALL[@]}" -o "$TMP/e.exr" &&
  $PM render scenes/cornell.scene "${SMALL[@]}" --rep-eval lazy --rep-every 5 -o "$TMP/l.exr" &&
  ! cmp -s "$TMP/e.exr" "$TMP/l.exr"
}
check "negative control: lazy with other representatives differs" lazy_control

# The furnace sphere (radius 1): a point at distance d lies d^2/2 from the
# tangent plane, and every radius is at most the cap (0.17), so tau 0.1
# passes every representative and photon in range; with --nn 100 every eye
# hit also lies within its nearest representative's kNN radius (with 50 a
# rare one does not, and a farther representative answers)
FURNACE=(scenes/furnace.scene --photons 100000 --nn 100 --width 96 --height 72 --quiet --method precomputed)
gate_unchanged() { # extra options...
  $PM render "${FURNACE[@]}" "$@" -o "$TMP/n.exr" &&
  $PM render "${FURNACE[@]}" "$@" --rep-gate plane -o "$TMP/g.exr" --stats "$TMP/g.json" &&
  cmp "$TMP/n.exr" "$TMP/g.exr" && [ "$(stat "$TMP/g.json" rep_fallbacks)" -eq 0 ] &&
  grep -q '"rep_gate": "plane"' "$TMP/g.json"
}
check "--rep-gate plane on the furnace sphere: the same image, no fallback" gate_unchanged
check "--rep-gate plane on the furnace sphere with --bias-correction: the same image" gate_unchanged --bias-correction
# where surfaces lie closer than a kNN radius (thin slabs, their corners),
# some eye samples find no representative that passes: they fall back
gate_falls_back() {
  $PM render scenes/slabs.scene --photons 50000 --width 64 --height 48 --quiet --method precomputed \
      --rep-gate plane --stats "$TMP/s.json" -o "$TMP/s.exr" &&
  $PM render scenes/slabs.scene --photons 50000 --width 64 --height 48 --quiet --method precomputed -o "$TMP/p.exr" &&
  [ "$(stat "$TMP/s.json" rep_fallbacks)" -gt 0 ] && ! cmp -s "$TMP/s.exr" "$TMP/p.exr"
}
check "--rep-gate plane among thin slabs: rep_fallbacks > 0, another image" gate_falls_back
# and a tolerance tighter than the sphere's curvature allows fails there too
gate_tight() {
  $PM render "${FURNACE[@]}" --rep-gate plane --rep-gate-tau 0.001 --stats "$TMP/t.json" -o "$TMP/t.exr" &&
  [ "$(stat "$TMP/t.json" rep_fallbacks)" -gt 0 ]
}
check "--rep-gate-tau 0.001 on the sphere: fallbacks" gate_tight

check "render --help lists the variants with default and range" bash -c \
  "$PM render --help | grep -A1 -E '^  --rep-eval eager\|lazy' | grep -q '(default: eager)' &&
   $PM render --help | grep -A1 -E '^  --rep-gate none\|plane' | grep -q '(default: none)' &&
   $PM render --help | grep -A1 -E '^  --rep-gate-tau T' | grep -q '(default: 0.1; a number in \[0.001, 1\])'"

# refused where they cannot apply, with the reason
C=(scenes/cornell.scene --photons 1000 --width 8 --height 8 --quiet)
check "--rep-eval lazy with the conventional method: exit 2" \
  expect_exit 2 "--rep-eval lazy evaluates the representatives of the precomputed method" $PM render "${C[@]}" --rep-eval lazy
check "--rep-gate plane with the conventional method: exit 2" \
  expect_exit 2 "--rep-gate plane chooses among the representatives" $PM render "${C[@]}" --rep-gate plane
check "--rep-gate-tau without --rep-gate plane: exit 2" \
  expect_exit 2 "--rep-gate-tau is the plane gate's tolerance" $PM render "${C[@]}" --method precomputed --rep-gate-tau 0.2
check "--rep-gate plane with --rep-tree shared: exit 2" \
  expect_exit 2 "--rep-tree shared has none" $PM render "${C[@]}" --method precomputed --rep-gate plane --rep-tree shared
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
