#!/usr/bin/env bash
# beyond.test.sh: `make beyond` end to end at a tiny size (cornell at 32x24,
# a two-cell-wide grid, two seeds, one tau), then experiments/analysis/beyond.py
# on doctored copies of its runs CSVs: a variant whose renders are missing,
# or a case without the paper's rule, is refused; a variant made slower in
# its CSV loses its speed-up (the verdict follows the data).
cd "$(dirname "$0")/.." || exit 1
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}
# (the unit cases of beyond.py, tests/test_beyond.py, run in tests/pytest.test.sh)
if ! "$PY" -c 'import numpy, pandas, scipy, OpenImageIO, matplotlib' 2>/dev/null || [ ! -x "$PM" ]; then
  echo "skipped: needs $PM and numpy, pandas, scipy, OpenImageIO, matplotlib"; echo "$PASS passed, $FAIL failed, 1 skipped"; [ "$FAIL" -eq 0 ]; exit
fi
R=$TMP/r
ARGS=(SCENES=scenes/cornell.scene SIZE=32x24 BEYOND_SIZES=32x24 "PHOTONS=2000 4000" "NNS=10 20" SEEDS=2
      BEYOND_TAUS=0.1 CONV_REF_PHOTONS=20000 CONV_REF_NN=50 BOOTSTRAP=200 RESULTS="$R" FIGURES="$R/figures")
make -s beyond "${ARGS[@]}" > "$TMP/make.log" 2>&1; rc=$?
check "make beyond exits 0" test "$rc" -eq 0
[ "$rc" -eq 0 ] || sed 's/^/     /' "$TMP/make.log" | tail -n 20
check "beyond.md, beyond.csv and the figure exist" test -s "$R/beyond/beyond.md" -a -s "$R/beyond/beyond.csv" -a -s "$R/figures/beyond.png"
csv=$R/beyond/beyond.csv
col() { # VARIANT COLUMN: the value in beyond.csv
  "$PY" -c 'import pandas as pd, sys; t = pd.read_csv(sys.argv[1]); print(t.loc[t["variant"] == sys.argv[2], sys.argv[3]].iloc[0])' "$csv" "$1" "$2"
}
check "four variants: paper lazy gated0.1 lazygated0.1" \
  bash -c "[ \"\$($PY -c 'import pandas as pd,sys; print(\" \".join(pd.read_csv(sys.argv[1])[\"variant\"]))' $csv)\" = 'paper lazy gated0.1 lazygated0.1' ]"
check "the paper's rule evaluates every representative and never falls back" \
  bash -c "[ \"$(col paper evaluated_share)\" = 1.0 ] && [ \"$(col paper fallback_rate)\" = 0.0 ]"
check "lazy: at most every representative, same error as the paper's rule (the same images)" \
  bash -c "awk -v e=$(col lazy evaluated_share) 'BEGIN { exit !(e > 0 && e <= 1) }' && [ \"$(col lazy error_ratio)\" = \"$(col paper error_ratio)\" ]"
check "every row's fallback rate is a rate" \
  "$PY" -c 'import pandas as pd, sys; t = pd.read_csv(sys.argv[1]); assert ((t.fallback_rate >= 0) & (t.fallback_rate <= 1)).all()' "$csv"
check "where the error lies: lazy's excess equals the paper's (the same images), the edge pixels a share" "$PY" -c '
import pandas as pd, sys, numpy as np
t = pd.read_csv(sys.argv[1]).set_index("variant")
assert t.loc["lazy", "excess_relmse"] == t.loc["paper", "excess_relmse"], t.excess_relmse
assert 0 < t.loc["paper", "edge_pixels"] < 1, t.edge_pixels
assert t.excess_edge_share.dropna().map(np.isfinite).all()
assert (t.precompute_med_s >= 0).all() and (t.render_med_s > 0).all()' "$csv"
check "the report has the time and error-location table" grep -q '^## Where the time goes and where the error lies' "$R/beyond/beyond.md"
check "the report says per case whether the goal holds" grep -qE '^- \*\*cornell-32x24\*\* .*goal (holds|does not hold)' "$R/beyond/beyond.md"

# back to back: every (cell, seed) of the case is one group, conventional,
# paper, lazy, gated0.1, lazygated0.1, in that order at odd seeds and reversed
# at even ones (pair_pos 1..5 in the records)
check "each group has all five members, in order at seed 1 and reversed at seed 2" "$PY" - "$R/runs" <<'P2'
import glob, json, os, sys
root = sys.argv[1]
base = glob.glob(os.path.join(root, "cornell-32x24-*-beyond"))[0]
members = [(base, "conventional"), (base, "precomputed")] + [(base + "-" + v, "precomputed")
                                                             for v in ("lazy", "gated0.1", "lazygated0.1")]
groups = 0
for cell in ("p2000-n10", "p2000-n20", "p4000-n10", "p4000-n20"):
    for seed in (1, 2):
        pos = [json.load(open(f"{r}/{m}-paper-{cell}/seed{seed}.run.json"))["pair_pos"] for r, m in members]
        want = [1, 2, 3, 4, 5] if seed == 1 else [5, 4, 3, 2, 1]
        assert pos == want, (cell, seed, pos)
        groups += 1
assert groups == 8
P2
check "a group's positions are back to back in time (each member's files older than the next one's record)" "$PY" - "$R/runs" <<'P2'
import glob, json, os, sys
base = glob.glob(os.path.join(sys.argv[1], "cornell-32x24-*-beyond"))[0]
recs = [f"{base}/conventional-paper-p2000-n10/seed2.run.json", f"{base}/precomputed-paper-p2000-n10/seed2.run.json"]
recs += [f"{base}-{v}/precomputed-paper-p2000-n10/seed2.run.json" for v in ("lazy", "gated0.1", "lazygated0.1")]
by_pos = sorted(recs, key=lambda f: json.load(open(f))["pair_pos"])
t = [os.stat(f).st_mtime_ns for f in by_pos]
assert t == sorted(t), t
P2
# the launcher's group alone (experiments/launch.py, the command of the rule
# group): a member that fails, or a group interrupted, leaves none of its records
G=$TMP/g
mkdir -p "$G"
cat > "$TMP/pm-fail" <<EOF
#!/usr/bin/env bash
case " \$* " in *" --rep-eval lazy "*) echo "doctored renderer: fails" >&2; exit 1 ;; esac
exec $PWD/$PM "\$@"
EOF
cat > "$TMP/pm-slow" <<EOF
#!/usr/bin/env bash
case " \$* " in *" --rep-eval lazy "*) touch "$G/slow-started"; sleep 30 ;; esac
exec $PWD/$PM "\$@"
EOF
chmod +x "$TMP/pm-fail" "$TMP/pm-slow"
# launch PM SEED: one group of three members of one (cell, seed) at 8x6
launch() {
  "$PY" -m experiments.launch --pm "$1" --scene scenes/cornell.scene --width 8 --height 6 --subpixels 1 --threads 1 --repeats 1 \
    --of 3 --stem "paper-p500-n5/seed$2" --member "$G/a" conventional "" 1 --member "$G/a" precomputed "" 2 \
    --member "$G/b" precomputed "--rep-eval lazy" 3
}
export -f launch
export G PY
check "launch.py group: all three records after a good group" bash -c "launch '$PWD/$PM' 1 > /dev/null &&
  ls $G/a/conventional-paper-p500-n5/seed1.run.json $G/a/precomputed-paper-p500-n5/seed1.run.json $G/b/precomputed-paper-p500-n5/seed1.run.json"
check "launch.py group: a member that fails exits 1 and no record of the group stays (the ones made before it too)" bash -c "
  launch '$TMP/pm-fail' 1 > /dev/null 2>&1; rc=\$?; [ \$rc -eq 1 ] && ! ls $G/a/*/*.run.json $G/b/*/*.run.json 2>/dev/null"
check "negative control: the same failure at an even seed (lazy first) also leaves no record" bash -c "
  launch '$TMP/pm-fail' 2 > /dev/null 2>&1; rc=\$?; [ \$rc -eq 1 ] && ! ls $G/a/*/seed2.run.json $G/b/*/seed2.run.json 2>/dev/null"
rm -f "$G/slow-started"
setsid bash -c "launch '$TMP/pm-slow' 3" >/dev/null 2>&1 &
gpid=$!
for _ in $(seq 1 100); do [ -e "$G/slow-started" ] && break; sleep 0.1; done
kill -TERM -- -"$gpid" 2>/dev/null; wait "$gpid" 2>/dev/null
check "launch.py group killed during its third render leaves no record of the group (two were finished)" bash -c '
  [ -e '"$G"'/slow-started ] && ! ls '"$G"'/a/*/seed3.run.json '"$G"'/b/*/seed3.run.json 2>/dev/null'
check "launch.py refuses a member that is not ROOT METHOD ARGS K" expect_exit 2 'expected 4 arguments' \
  "$PY" -m experiments.launch --pm "$PM" --scene scenes/cornell.scene --width 8 --height 6 --subpixels 1 --of 1 \
  --stem paper-p500-n5/seed1 --member "$G/a" conventional

S=$R/beyond/studies
REF=$(ls "$R"/runs/cornell-convref-*/32x24.exr)
run_py() { # PAPER_CSV LAZY_CSV [more args]: beyond.py on the case with these two variants
  local p=$1 l=$2; shift 2
  "$PY" -m experiments.analysis.beyond --case c cornell 32x24 "$REF" --variant c paper "" "$p" \
    --variant c lazy "--rep-eval lazy" "$l" --bootstrap 200 --out "$TMP/o/beyond" "$@"
}
check "beyond.py on the real CSVs exits 0" run_py "$S/runs-cornell-32x24-paper.csv" "$S/runs-cornell-32x24-lazy.csv"
# negative control 1: one of lazy's renders marked missing
"$PY" - "$S/runs-cornell-32x24-lazy.csv" "$TMP/missing.csv" <<'P'
import pandas as pd, sys
t = pd.read_csv(sys.argv[1]); i = t.index[(t.role == "grid") & (t.method == "precomputed")][0]
t.loc[i, "status"] = "missing"; t.to_csv(sys.argv[2], index=False)
P
check "a variant with a missing render is refused" expect_exit 1 'renders missing' \
  run_py "$S/runs-cornell-32x24-paper.csv" "$TMP/missing.csv"
check "a case without the paper's rule is refused" expect_exit 1 'no --variant c paper' \
  "$PY" -m experiments.analysis.beyond --case c cornell 32x24 "$REF" --variant c lazy "" "$S/runs-cornell-32x24-lazy.csv" --out "$TMP/o/x"
# negative control 2: lazy's renders made 100x slower: its speed-up falls 100x
"$PY" - "$S/runs-cornell-32x24-lazy.csv" "$TMP/slow.csv" <<'P'
import pandas as pd, sys
t = pd.read_csv(sys.argv[1]); m = (t.role == "grid") & (t.method == "precomputed")
t.loc[m, "total_s"] = t.loc[m, "total_s"] * 100; t.to_csv(sys.argv[2], index=False)
P
run_py "$S/runs-cornell-32x24-paper.csv" "$S/runs-cornell-32x24-lazy.csv" > /dev/null 2>&1 && cp "$TMP/o/beyond.csv" "$TMP/real.csv"
check "a doctored CSV (lazy 100x slower) lowers lazy's paired ratio to the paper's rule 100x (and its equal-error speed-up, where both are defined) and it is no longer above 1.0" bash -c "
  $(declare -f run_py); PY=$PY REF=$REF TMP=$TMP
  run_py '$S/runs-cornell-32x24-paper.csv' '$TMP/slow.csv' >/dev/null && $PY -c '
import pandas as pd, sys
a = pd.read_csv(sys.argv[1]).set_index(\"variant\"); b = pd.read_csv(sys.argv[2]).set_index(\"variant\")
r = a.loc[\"lazy\", \"vs_paper_ratio\"] / b.loc[\"lazy\", \"vs_paper_ratio\"]
assert 99 < r < 101, r
sa, sb = a.loc[\"lazy\", \"speedup\"], b.loc[\"lazy\", \"speedup\"]
assert sa != sa or sb != sb or 99 < sa / sb < 101, (sa, sb)
assert b.loc[\"lazy\", \"above_one\"] == False and b.loc[\"lazy\", \"goal_met\"] == False
' $TMP/real.csv $TMP/o/beyond.csv"
# negative control 3: lazy's renders replaced by the conventional images of the same seeds: no excess error
"$PY" - "$S/runs-cornell-32x24-lazy.csv" "$TMP/same.csv" <<'P2'
import pandas as pd, sys
t = pd.read_csv(sys.argv[1]); m = (t.role == "grid") & (t.method == "precomputed")
conv = t[t.method == "conventional"].set_index(["photons", "nn", "seed"])["run"]
t.loc[m, "run"] = [conv.loc[k] for k in zip(t.loc[m, "photons"], t.loc[m, "nn"], t.loc[m, "seed"])]
t.to_csv(sys.argv[2], index=False)
P2
check "a doctored CSV (lazy's images = the conventional ones) has zero excess error and none to place" bash -c "
  $(declare -f run_py); PY=$PY REF=$REF TMP=$TMP
  run_py '$S/runs-cornell-32x24-paper.csv' '$TMP/same.csv' >/dev/null && $PY -c '
import pandas as pd, sys, math
b = pd.read_csv(sys.argv[1]).set_index(\"variant\")
assert b.loc[\"lazy\", \"excess_relmse\"] == 0.0 and math.isnan(b.loc[\"lazy\", \"excess_edge_share\"])
assert b.loc[\"paper\", \"excess_relmse\"] != 0.0
' $TMP/o/beyond.csv"
check "make beyond refuses SCENE=" expect_exit 2 'give SCENES=' make -s beyond SCENE=scenes/cornell.scene RESULTS="$R"
finish
