#!/usr/bin/env bash
# evaluate.test.sh: `make evaluate` end to end on a scene of its own
# (tests/evaluate/box.scene, not one of scenes/) at a tiny size: every
# stage's files, the report's sections and the converged reference's JSON;
# then the negative controls: a scene with a hole (tests/evaluate/open.scene)
# is stopped at the pilot, a deliberately wrong POV-Ray reference (the red
# wall green, tests/evaluate/box-wrong.scene) is reported as a disagreement,
# a knob evaluate does not read is refused, and a rerun renders no POV-Ray
# reference again (the cache). Skipped without povray/oiiotool.
cd "$(dirname "$0")/.." || exit 1
. tests/lib.sh
unset MAKEFLAGS MFLAGS MAKELEVEL
if ! command -v povray > /dev/null || ! command -v oiiotool > /dev/null; then
  echo "skipped: povray or oiiotool missing (make deps)"; echo "0 passed, 0 failed, 1 skipped"; exit 0
fi
make -s build/photonmap > /dev/null || { echo "FAIL build"; echo "0 passed, 1 failed"; exit 1; }
KNOBS=(SIZE=32x24 SEEDS=2 PHOTONS="4000 8000" NNS="10 30" BOOTSTRAP=200 CONV_REF_FACTOR=20 CONV_REF_NN=100
       EVAL_CACHE="$TMP/cache" RESULTS="$TMP/results")
OUT=$TMP/box
ev() { nice -n 5 make --no-print-directory evaluate "${KNOBS[@]}" "$@"; }

rc=0
ev SCENE=tests/evaluate/box.scene OUT="$OUT" > "$TMP/box.log" 2>&1 || rc=$?
check "make evaluate exits 0" test "$rc" -eq 0
check "a progress line per stage" bash -c "for s in 1 2 3 4 5; do grep -q \"^evaluate: \[\$s/5\]\" '$TMP/box.log' || exit 1; done"
check "stage 1: pilot files" test -s "$OUT/pilot/pilot.json" -a -s "$OUT/pilot/pilot.stats.json"
check "stage 2: POV-Ray references and the thickness" test -s "$OUT/pov/reference.exr" -a -s "$OUT/pov/fast.exr" -a -s "$OUT/pov/thickness.json"
ref=$(ls "$OUT"/reference/*/32x24.exr 2>/dev/null | head -n 1)
check "stage 3: the converged reference and its JSON" test -s "$ref" -a -s "${ref%.exr}.json"
check "stage 3: the JSON holds noise, bias and the settings" /usr/bin/python3 -c '
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["noise"] > 0 and math.isfinite(d["bias"]) and d["bias"] >= 0, d
s = d["settings"]
assert s["estimate"] == "corrected" and len(s["seeds"]) >= 2 and not set(s["seeds"]) & set(s["grid_seeds"]), s
assert s["photons"] == 20 * 8000 and s["half_photons"] == 80000, s' "${ref%.exr}.json"
check "stage 3: the references agree on the right scene" /usr/bin/python3 -c '
import json, sys; assert json.load(open(sys.argv[1]))["agree"] == "full"' "$OUT/crosscheck.json"
check "stage 4: the grid and its variants" test -s "$OUT/grid/runs.csv" -a -s "$OUT/grid/equal-error.csv" -a -s "$OUT/grid/runs-lazy.csv" -a -s "$OUT/grid/runs-plane-lookup.csv"
check "stage 4: the final-gathering grids (EVAL_GATHERS) against the map seen directly" test -s "$OUT/gather/runs-N4.csv" -a -s "$OUT/gather/runs-N16.csv" -a -s "$OUT/gather/gather.csv" -a -s "$OUT/gather/gather.md"
check "stage 4: the gather grids ran --gather N" grep -q -- '--gather 16' "$OUT/gather/table-N16.md"
check "stage 5: report and images" test -s "$OUT/report.md" -a -s "$OUT/difference.png" -a -s "$OUT/conventional.png" -a -s "$OUT/precomputed.png" -a -s "$OUT/equal-error.png"
check "the report's sections" bash -c "for s in '## Verdict' '## Pilot' '## References' '### The reference' '## Images' '## Time ratios' '## Equal-error speed-up' '## Final gathering' '## Settings'; do grep -qF \"\$s\" '$OUT/report.md' || { echo \"missing \$s\"; exit 1; }; done"
check "the report prints the reference's measured error" grep -q 'Its own error in relmse: noise [0-9.e-]* (from the seeds), kernel bias' "$OUT/report.md"
check "the verdict is a sentence from the data" grep -qE 'corrected estimate: (at the tightest target|undetermined)' "$OUT/report.md"
check "the verdict names final gathering and the cheapest configuration per target" grep -qE '^Final gathering \(--gather N.*The cheapest configuration per relMSE target over every mode' "$OUT/report.md"

# a rerun renders no POV-Ray reference (cached) and no grid render
rc=0
ev SCENE=tests/evaluate/box.scene OUT="$OUT" > "$TMP/rerun.log" 2>&1 || rc=$?
check "a rerun renders nothing again" bash -c "[ $rc -eq 0 ] && ! grep -q 'rendered at\|^run \|P_e=.* seed ' '$TMP/rerun.log'"
# the same scene in another OUT: POV-Ray from the cache
rc=0
nice -n 5 make --no-print-directory evaluate-references "${KNOBS[@]}" SCENE=tests/evaluate/box.scene OUT="$TMP/box2" \
  > "$TMP/box2.log" 2>&1 || rc=$?
check "the POV-Ray cache serves another OUT" bash -c "[ $rc -eq 0 ] && [ \$(grep -c ': cached' '$TMP/box2.log') -eq 2 ]"

# negative control: photons escape through the missing ceiling
rc=0
ev SCENE=tests/evaluate/open.scene OUT="$TMP/open" > "$TMP/open.log" 2>&1 || rc=$?
check "control: an open scene is stopped at the pilot" bash -c "[ $rc -ne 0 ] && grep -q 'photons escape the scene' '$TMP/open.log' && [ ! -e '$TMP/open/pov' ] && [ ! -e '$TMP/open/report.md' ] && [ ! -e '$TMP/open/pilot/pilot.json' ]"
# negative control: the camera shut inside an opaque sphere
{ grep -v '^#' tests/evaluate/box.scene; echo "sphere center 0 1 0.9  radius 0.08  material white"; } > "$TMP/shut.scene"
rc=0
ev SCENE="$TMP/shut.scene" OUT="$TMP/shut" > "$TMP/shut.log" 2>&1 || rc=$?
check "control: a camera shut in a sphere is stopped at the pilot" bash -c "[ $rc -ne 0 ] && grep -q 'shut inside an opaque sphere' '$TMP/shut.log' && [ ! -e '$TMP/shut/pov' ]"
# negative control: POV-Ray renders a scene with another material
rc=0
nice -n 5 make --no-print-directory evaluate-references "${KNOBS[@]}" SCENE=tests/evaluate/box.scene \
  EVAL_POV_SCENE=tests/evaluate/box-wrong.scene OUT="$TMP/wrong" > "$TMP/wrong.log" 2>&1 || rc=$?
check "control: a wrong POV-Ray reference is reported as a disagreement" bash -c "[ $rc -eq 0 ] && grep -q 'DISAGREE' '$TMP/wrong.log' && /usr/bin/python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d[\"agree\"] == \"none\" and \"b2\" in d, d' '$TMP/wrong/crosscheck.json'"
# knobs: refused when not read, SCENE required
check "control: a knob evaluate does not read is refused" expect_exit 2 'REF is not read by evaluate' make -s evaluate SCENE=tests/evaluate/box.scene REF=x.exr
check "control: SCENE is required" expect_exit 2 'give SCENE=' make -s evaluate
check "control: a grid seed as the reference's is refused" expect_exit 2 'are the grid.s' \
  make -s evaluate "${KNOBS[@]}" SCENE=tests/evaluate/box.scene OUT="$TMP/seed" CONV_REF_SEEDS="1 1000002"

# the thickness rule: a box behind a rectangle entering another shape
cat > "$TMP/cross.scene" <<'SC'
camera position 0 1 0.9  look_at 0 1 -1  up 0 1 0  fov 60
light point position 0 1.5 0  power 1 1 1
material w lambert rho 0.5 0.5 0.5
rect corner -1 0 -1  edge1 2 0 0  edge2 0 0 2  material w
rect corner -0.5 -0.5 0  edge1 1 0 0  edge2 0 1 0  material w
SC
cat > "$TMP/near.scene" <<'SC'
camera position 0 1 0.9  look_at 0 1 -1  up 0 1 0  fov 60
light point position 0 1.5 0  power 1 1 1
material w lambert rho 0.5 0.5 0.5
rect corner -1 0.5 -1  edge1 2 0 0  edge2 0 0 2  material w
rect corner -0.5 0.499 -0.5  edge1 1 0 0  edge2 0 0 1  material w
SC
check "thickness: a rectangle crossing another is refused with both lines" expect_exit 2 'line 4 and the shape of line 5 cross|line 5 and the shape of line 4 cross' \
  /usr/bin/python3 -m experiments.analysis.evaluate thickness --scene "$TMP/cross.scene" --out "$TMP/cross.json"
check "thickness: a shape 1 mm behind a lit face gets a thinner box" bash -c \
  "[ \$(/usr/bin/python3 -m experiments.analysis.evaluate thickness --scene '$TMP/near.scene' --out '$TMP/near.json') = 0.0001 ]"
check "thickness: the room of box.scene keeps the default" bash -c \
  "[ \$(/usr/bin/python3 -m experiments.analysis.evaluate thickness --scene tests/evaluate/box.scene --out '$TMP/b.json') = 0.001 ]"
# reference.py's error terms against known values (synthetic seeds of
# variance sigma^2, the half-photon mean's bias twice the full one's), with
# a control without bias, and corrected() / check()
check "reference: noise and bias of synthetic seeds match their known values" /usr/bin/python3 -c '
import numpy as np
from experiments.analysis import reference as R
rng = np.random.default_rng(5)
r = np.full((200, 200, 3), 0.5); sig = 0.05; b = 0.02
w = 1 / ((0.5 + b) ** 2 + 0.01)  # relMSE weight at the mean
for S in (2, 3, 4):
    full = [r + b + rng.normal(0, sig, r.shape) for _ in range(S)]
    half = [r + 2 * b + rng.normal(0, sig, r.shape) for _ in range(S)]
    m = R.measure(full, half)
    assert abs(m["noise"] / (w * sig**2 / S) - 1) < 0.05, (S, m)
    assert abs(m["bias"] / (w * b**2) - 1) < 0.15, (S, m)
full = [r + rng.normal(0, sig, r.shape) for _ in range(2)]
half = [r + rng.normal(0, sig, r.shape) for _ in range(2)]
assert abs(R.measure(full, half)["bias_raw"]) < 0.05 * w * b**2, R.measure(full, half)
assert R.corrected(0.01, {"noise": 0.002}) == 0.008 and R.corrected(0.01, None) == 0.01
assert R.check({"noise": 0.002, "bias": 0.0}, 0.01)[0] is False
assert R.check({"noise": 0.0005, "bias": 0.0009}, 0.01)[0] is True'
finish
