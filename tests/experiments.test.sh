#!/usr/bin/env bash
# experiments.test.sh: the experiment layer end to end on a tiny grid
# (32x24, 2,000-4,000 photons, 3 seeds): the metrics command line; `make
# reproduce-table` (one make target per render, progress lines, refused
# renders as "not applicable", resume, added seeds, runs.csv / table1.csv
# columns by name, table1.md, equal-error.md); `make resolution`. A wrapper
# around the renderer plays a renderer that refuses one combination (exit 2)
# or fails (exit 1), so those paths are tested whatever the renderer does.
cd "$(dirname "$0")/.." || exit 1
source tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}
IM="$PY -m experiments.analysis.metrics"
R=$TMP/results
REAL_PM=$(realpath "$PM")
ROOT=$R/runs/cornell-32x24-s2-t1

# the renderer as the grid sees it: refuses precomputed with P_e = 2000 and
# n = 20 (exit 2), fails (exit 1) with n = FAIL_NN, logs every command line
cat > "$TMP/pm" <<EOF
#!/usr/bin/env bash
echo "\$*" >> "$TMP/pm.log"
case " \$* " in *" --method precomputed --photons 2000 --nn 20 "*) echo "photonmap: test refusal: precomputed with n=20" >&2; exit 2 ;; esac
case " \$* " in *" --nn \${FAIL_NN:-none} "*) echo "photonmap: test failure" >&2; exit 1 ;; esac
exec "$REAL_PM" "\$@"
EOF
chmod +x "$TMP/pm"
# one process per render (TIME_PROCESSES=1): the progress lines and the
# command log count renders; two processes are checked after the grid
ARGS=(SIZE=32x24 "PHOTONS=2000 4000" "NNS=10 20" SEEDS=3 ESTIMATES=paper RESULTS="$R" PM="$TMP/pm"
      REF="$TMP/ref.exr" REF_FAST="$TMP/fast.exr" BOOTSTRAP=200 "EE_TARGETS=0.1 0.05" TIME_PROCESSES=1)
# pycheck 'CODE': python with pandas as pd, numpy as np, R = the results dir
pycheck() { R="$R" "$PY" -c "import os, math, numpy as np, pandas as pd; R = os.environ['R']; $1"; }

# the metrics command line (experiments/analysis/metrics.py) on two tiny renders
$PM render scenes/cornell.scene --width 16 --height 12 --photons 2000 --nn 10 -o "$TMP/a.exr" --quiet
$PM render scenes/cornell.scene --width 16 --height 12 --photons 2000 --nn 10 --method precomputed -o "$TMP/b.exr" --quiet
$PM render scenes/cornell.scene --width 8 --height 6 --photons 2000 --nn 10 -o "$TMP/c.exr" --quiet
check "metrics: identical images give 0 and inf" \
  bash -c "$IM $TMP/a.exr $TMP/a.exr | grep -q '^relmse=0 rmse=0 psnr=inf pixels=192 peak=1$'"
check "metrics: different images give a positive error, CSV form" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --header | awk -F, 'NR==1 && \$0==\"relmse,rmse,psnr,pixels,peak\" {h=1} NR==2 && \$1>0 && \$2>0 && \$3>0 && \$4==192 {v=1} END {exit !(h && v)}'"
check "metrics: --mask restricts the pixels" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --mask $TMP/a.exr | grep -q 'pixels=1[0-9][0-9] '"
check "metrics: --peak max uses the reference maximum" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --peak max | grep -qv 'peak=1$'"
check "metrics: size mismatch is an error" \
  expect_exit 2 "size mismatch" $IM "$TMP/a.exr" "$TMP/c.exr"
check "metrics: missing file is an error" expect_exit 2 "nonexistent" $IM "$TMP/a.exr" /nonexistent.exr

# a reference and a "fast reference" of the tiny size: two high-photon renders
$PM render scenes/cornell.scene --width 32 --height 24 --photons 40000 --nn 100 -o "$TMP/ref.exr" --quiet
$PM render scenes/cornell.scene --width 32 --height 24 --photons 40000 --nn 100 --seed 2 -o "$TMP/fast.exr" --quiet

make -s reproduce-table "${ARGS[@]}" > "$TMP/grid.log" 2>&1
check "reproduce-table: exits 0, one progress line per render" \
  bash -c "grep -q '^run 1/24 conventional paper P_e=2000 n=10 seed 1: total [0-9.]* s, cpu [0-9.]* s$' $TMP/grid.log &&
           grep -q '^run 20/24 precomputed paper P_e=2000 n=20 seed 3: not applicable' $TMP/grid.log &&
           grep -q '^run 24/24 precomputed paper P_e=4000 n=20 seed 3: total' $TMP/grid.log &&
           [ \$(grep -c '^run ' $TMP/grid.log) -eq 24 ] && grep -q 'wrote .*equal-error.md' $TMP/grid.log"
check "reproduce-table: one directory per cell, one record per render, no temporary file" \
  bash -c "[ \$(ls -d $ROOT/*/ | wc -l) -eq 8 ] && [ \$(ls $ROOT/*/seed*.run.json | wc -l) -eq 24 ] &&
           [ \$(ls $ROOT/*/seed*.exr | wc -l) -eq 21 ] && ! ls $ROOT/*/*.tmp.* 2>/dev/null | grep -q ."
check "reproduce-table: each render has its own seed, corrected renders add --bias-correction only" \
  bash -c "grep -q -- '--nn 10 --seed 3 ' $TMP/pm.log && ! grep -q -- '--bias-correction' $TMP/pm.log"
check "runs.csv: one row per render, the columns by name, refused renders not applicable" pycheck '
r = pd.read_csv(f"{R}/table1/runs.csv")
need = ["scene", "size", "subpixels", "threads", "tag", "method", "estimate", "photons", "nn", "seed", "rep_every",
        "trace_s", "build_s", "precompute_s", "render_s", "total_s", "cpu_s", "photons_stored", "representatives",
        "empty_estimates", "relmse_ref", "rmse_ref", "psnr_ref", "relmse_conv", "exit", "status"]
assert not [c for c in need if c not in r.columns], [c for c in need if c not in r.columns]
assert len(r) == 24 and set(r["seed"]) == {1, 2, 3} and set(r["photons"]) == {2000, 4000}, r
ref = (r["method"] == "precomputed") & (r["nn"] == 20) & (r["photons"] == 2000)
assert (r.loc[ref, "status"] == "refused").all() and (r.loc[ref, "exit"] == 2).all()
assert r.loc[ref, "message"].str.contains("test refusal").all() and r.loc[ref, "relmse_ref"].isna().all()
ok = r[~ref]
assert (ok["status"] == "ok").all() and (ok["total_s"] > 0).all() and (ok["cpu_s"] >= 0).all()
assert (ok["relmse_ref"] > 0).all() and (ok["psnr_ref"] > 0).all() and (ok["threads"] == 1).all()
assert (ok["nmse_ref"] > 0).all() and ok["nmse_ref"].notna().all()
conv = ok["method"] == "conventional"
assert (ok.loc[conv, "relmse_conv"] == 0).all() and (ok.loc[~conv, "relmse_conv"] > 0).all()
assert (ok.loc[~conv, "representatives"] > 0).all() and (ok["photons_stored"] > 0).all()
'
check "runs.csv: relmse_ref of a render equals the metrics command line on its EXR" \
  bash -c "want=\$($IM $ROOT/precomputed-paper-p4000-n10/seed2.exr $TMP/ref.exr --csv | cut -d, -f1);
           got=\$(R=$R $PY -c 'import os, pandas as pd; r = pd.read_csv(os.environ[\"R\"] + \"/table1/runs.csv\");
print(r[(r.method == \"precomputed\") & (r.photons == 4000) & (r.nn == 10) & (r.seed == 2)].relmse_ref.iloc[0])');
           awk -v a=\"\$want\" -v b=\"\$got\" 'BEGIN { d = a - b; exit !(d < 1e-6 && d > -1e-6 && a > 0) }'"
check "table1.csv: a row per (P_e, n, method), error columns by name, bias + variance = mean" pycheck '
t = pd.read_csv(f"{R}/table1/table1.csv")
need = ["photons", "nn", "method", "paper_s", "paper_ratio_percent", "total_median_s", "total_min_s", "total_max_s",
        "cpu_median_s", "trace_median_s", "build_median_s", "precompute_median_s", "render_median_s",
        "ratio_percent", "ratio_ci95_lo", "ratio_ci95_hi", "cpu_ratio_percent", "relmse_ref_mean", "relmse_ref_ci95",
        "bias_ref", "variance_ref", "relmse_conv_mean", "relmse_conv_ci95", "relmse_ref_floor", "seeds"]
assert not [c for c in need if c not in t.columns], [c for c in need if c not in t.columns]
assert len(t) == 8
ok = t[t["seeds"] == 3]
assert len(ok) == 7 and (t.loc[t["seeds"] == 0, "method"] == "precomputed").all()
assert t.loc[t["seeds"] == 0, "relmse_ref_mean"].isna().all()
assert np.allclose(ok["bias_ref"] + ok["variance_ref"], ok["relmse_ref_mean"], rtol=1e-5, atol=0)
assert (ok["relmse_ref_ci95"] > 0).all() and (ok["variance_ref"] > 0).all()
assert (ok["total_min_s"] <= ok["total_median_s"]).all() and (ok["total_median_s"] <= ok["total_max_s"]).all()
c = ok[ok["method"] == "conventional"]
assert (c["ratio_percent"] == 100).all() and (ok.loc[ok["method"] == "precomputed", "ratio_percent"] > 0).all()
p = ok[ok["method"] == "precomputed"]
assert (p["ratio_ci95_lo"] <= p["ratio_percent"]).all() and (p["ratio_percent"] <= p["ratio_ci95_hi"]).all()
assert (p["relmse_conv_mean"] > 0).all() and t["paper_s"].isna().all()
'
check "pairs: each (cell, seed) rendered back to back, the order alternating with the seed (pair_pos, the command log)" pycheck '
r = pd.read_csv(f"{R}/table1/runs.csv")
assert set(r["pair_pos"]) == {1, 2}, r["pair_pos"]
first = r[r["pair_pos"] == 1]
assert (first.loc[first["seed"] % 2 == 1, "method"] == "conventional").all(), first
assert (first.loc[first["seed"] % 2 == 0, "method"] == "precomputed").all(), first
assert len(first) == 12 and first.groupby(["photons", "nn", "seed"]).size().eq(1).all()
log = [l for l in open(os.path.join(os.path.dirname(R), "pm.log")) if "--seed" in l and "--width 32" in l]
key = lambda l: (l.split("--photons ")[1].split()[0], l.split("--nn ")[1].split()[0], l.split("--seed ")[1].split()[0])
assert len(log) == 24 and all(key(log[i]) == key(log[i + 1]) for i in range(0, 24, 2)), log
'
check "table1.csv: paired time ratios with the drift control, the paired error difference with a verdict" pycheck '
t = pd.read_csv(f"{R}/table1/table1.csv")
p = t[(t["method"] == "precomputed") & (t["seeds"] == 3)]
need = ["pairs", "paired_ratio_percent", "paired_ratio_ci95_lo", "paired_ratio_ci95_hi", "paired_cpu_ratio_percent",
        "trace_ratio_percent", "trace_ratio_ci95_lo", "trace_ratio_ci95_hi", "relmse_diff_mean", "relmse_diff_lo",
        "relmse_diff_hi", "relmse_diff_p", "relmse_diff_p_holm", "relmse_diff_delta", "relmse_diff_verdict"]
assert not [c for c in need if c not in t.columns], [c for c in need if c not in t.columns]
assert len(p) == 3 and (p["pairs"] == 3).all()
assert (p["paired_ratio_ci95_lo"] <= p["paired_ratio_percent"]).all() and (p["paired_ratio_percent"] <= p["paired_ratio_ci95_hi"]).all()
assert (p["trace_ratio_percent"] > 0).all() and (p["trace_ratio_ci95_lo"] <= p["trace_ratio_percent"]).all(), p["trace_ratio_percent"]
assert (p["relmse_diff_p_holm"] >= p["relmse_diff_p"]).all()
assert set(p["relmse_diff_verdict"]) <= {"higher", "lower", "equivalent", "undetermined"}
r = pd.read_csv(f"{R}/table1/runs.csv")
c = r[(r.method == "conventional") & (r.photons == 4000) & (r.nn == 10)].set_index("seed").relmse_ref
q = r[(r.method == "precomputed") & (r.photons == 4000) & (r.nn == 10)].set_index("seed").relmse_ref
row = p[(p.photons == 4000) & (p.nn == 10)].iloc[0]
assert abs(row["relmse_diff_mean"] - (q - c).mean()) < 1e-6 * abs(c.mean()), (row["relmse_diff_mean"], (q - c).mean())
md = open(f"{R}/table1/table1.md").read()
assert "## Paired: precomputed against conventional, the same seed (paper estimate)" in md and "drift" in md
'
check "table1.csv: the reference floor is the fast reference's relMSE" \
  bash -c "want=\$($IM $TMP/fast.exr $TMP/ref.exr --csv | cut -d, -f1);
           got=\$(R=$R $PY -c 'import os, pandas as pd; print(pd.read_csv(os.environ[\"R\"] + \"/table1/table1.csv\").relmse_ref_floor.iloc[0])');
           awk -v a=\"\$want\" -v b=\"\$got\" 'BEGIN { d = a - b; exit !(d < 1e-6 && d > -1e-6 && a > 0) }'"
check "table1.md: provenance, the tables, the refusal, no nan" \
  bash -c "grep -q 'Machine: .*threads per render: 1' $R/table1/table1.md && grep -q 'Commit: ' $R/table1/table1.md &&
           grep -q 'load average at the start of the renders' $R/table1/table1.md && grep -q 'Seeds: 1 2 3' $R/table1/table1.md &&
           grep -q '^| 4000 | 10 | n/a | n/a | n/a | [0-9.]* ([0-9.]*-[0-9.]*) | [0-9.]* (' $R/table1/table1.md &&
           grep -q '^| 2000 | 10 | precomputed | 3 | [0-9.e-]* ± [0-9.e-]* | [0-9.e-]*\\( ≤floor\\)\\? | [0-9.e-]* | [0-9.e-]* ± ' $R/table1/table1.md &&
           grep -q '^| 2000 | 20 | precomputed | 0 | not applicable' $R/table1/table1.md &&
           grep -q 'test refusal: precomputed with n=20' $R/table1/table1.md && grep -q '^## What the intervals allow us to say' $R/table1/table1.md &&
           grep -q 'Reference floor: relMSE of' $R/table1/table1.md && ! grep -qi 'nan' $R/table1/table1.md"
check "equal-error: Markdown with fronts and targets, CSV by name" pycheck '
e = pd.read_csv(f"{R}/table1/equal-error.csv")
need = ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction", "conventional_s", "precomputed_s"]
assert not [c for c in need if c not in e.columns], e.columns
t = e[e["kind"] == "target"]
assert len(t) == 2 and (e["estimate"] == "paper").all() and list(t["target"]) == [0.1, 0.05], e
c, tight = e[e["kind"] == "curve"], e[e["kind"] == "tightest"]
md = open(f"{R}/table1/equal-error.md").read()
# 41 targets over the common range of the fronts (one when that range is a
# single error, none when the millisecond times of this tiny grid leave the fronts no common range)
if len(tight):
    assert len(c) in (1, 41) and len(tight) == 1 and tight["target"].iloc[0] == c["target"].min(), e
    assert (c["target"].diff().dropna() > 0).all() and c["defined_fraction"].between(0, 1).all()
    d = c[np.isfinite(c["lo"])]
    assert ((d["lo"] <= d["speedup"] * 1.000001) | (d["defined_fraction"] < 1)).all() and (d["lo"] <= d["hi"]).all()
    assert os.path.getsize(f"{R}/table1/equal-error.png") > 5000
    assert "The tightest target both fronts reach" in md and "The curve" in md, md
else:
    assert len(c) == 0 and "no tightest target both reach, and no curve" in md, md
assert "# Speed-up at equal error" in md and "## paper estimate" in md and "| relMSE target |" in md, md
assert "| 0.1 |" in md and "| 0.05 |" in md and "EE_TARGETS=0.1 0.05" in md, md
assert "nan" not in md.lower()
'

# resume: nothing to render again; one missing render is the only one re-rendered
make -s reproduce-table "${ARGS[@]}" > "$TMP/grid2.log" 2>&1
check "reproduce-table: a second run renders nothing and rewrites the tables" \
  bash -c "! grep -q '^run ' $TMP/grid2.log && grep -q 'wrote .*table1.md' $TMP/grid2.log"
rm "$ROOT/conventional-paper-p2000-n20/seed2.run.json"
make -s reproduce-table "${ARGS[@]}" > "$TMP/grid3.log" 2>&1
check "reproduce-table: resumes only the missing render's pair, both renders, back to back in the seed's order" \
  bash -c "[ \$(grep -c '^run ' $TMP/grid3.log) -eq 2 ] &&
           grep '^run ' $TMP/grid3.log | head -n 1 | grep -q '^run 12/24 precomputed paper P_e=2000 n=20 seed 2: not applicable' &&
           grep '^run ' $TMP/grid3.log | tail -n 1 | grep -q '^run 11/24 conventional paper P_e=2000 n=20 seed 2: total'"
make -s reproduce-table "${ARGS[@]}" SEEDS=4 > "$TMP/grid4.log" 2>&1
check "reproduce-table: SEEDS=4 adds the fourth seed's renders only" \
  bash -c "[ \$(grep -c '^run .* seed 4: ' $TMP/grid4.log) -eq 8 ] && [ \$(grep -c '^run ' $TMP/grid4.log) -eq 8 ] &&
           grep -q 'Seeds: 1 2 3 4' $R/table1/table1.md"
make -s reproduce-table "${ARGS[@]}" SEEDS=5 FAIL_NN=10 > "$TMP/grid5.log" 2>&1; rc=$?
check "reproduce-table: a failing render (exit 1) stops make and records nothing" \
  bash -c "[ $rc -ne 0 ] && grep -q 'failed (exit 1)' $TMP/grid5.log && ! ls $ROOT/conventional-paper-p2000-n10/seed5.* 2>/dev/null | grep -q ."
make -s list-runs "${ARGS[@]}" > "$TMP/list.txt" 2>&1
check "reproduce-table: list-runs names every render's target" \
  bash -c "[ \$(wc -l < $TMP/list.txt) -eq 24 ] &&
           head -n 1 $TMP/list.txt | grep -q 'runs/cornell-32x24-s2-t1/conventional-paper-p2000-n10/seed1.run.json$'"
# two processes per render (TIME_PROCESSES' default): one cell, two seeds,
# the pm log's new lines in the order the renders ran; the gauge off
# (TIME_GAUGE=0: it adds processes where the times say so, and the order
# checked here is the rounds'; tests/test_processes.py tests the gauge)
: > "$TMP/pm.log"
make -s reproduce-table "${ARGS[@]}" PHOTONS=2000 NNS=10 SEEDS=2 RESULTS="$TMP/two" TIME_PROCESSES=2 TIME_GAUGE=0 > "$TMP/two.log" 2>&1
check "TIME_PROCESSES=2: each render in two processes, the methods alternating (A B B A), times the minima over both" pycheck '
log = [l.split("--method ")[1].split()[0][0] + l.split("--seed ")[1].split()[0] for l in open(os.path.join(os.path.dirname(R), "pm.log")) if "--width 32" in l]
assert log == ["c1", "p1", "p1", "c1", "p2", "c2", "c2", "p2"], log
r = pd.read_csv(os.path.join(os.path.dirname(R), "two", "table1", "runs.csv"))
assert (r["processes"] == 2).all() and (r["repeats"] >= 6).all() and (r["gauge_added"] == 0).all(), r[["processes", "repeats"]]
import json
for _, row in r.iterrows():
    st = json.load(open(row["run"] + ".stats.json"))
    assert st["time_s"]["total"] == min(st["time_s_repeats"]["total"]) == min(st["time_s_processes"]["total"])
    assert abs(row["total_s"] - st["time_s"]["total"]) < 1e-9
'
check "reproduce-table: REPEATS is refused with the new name" \
  expect_exit 2 "REPEATS is gone: every study target reads SEEDS" make -s reproduce-table "${ARGS[@]}" REPEATS=2
check "reproduce-table: a missing reference named by REF is an error" \
  bash -c "! make -s reproduce-table ${ARGS[*]} REF=$TMP/missing.exr > $TMP/grid6.log 2>&1 && grep -q 'reference .*missing.exr not found' $TMP/grid6.log"
make -s reproduce-runs "${ARGS[@]}" PM="$PM" ESTIMATES=corrected PHOTONS=2000 NNS=10 SEEDS=1 > "$TMP/corr.log" 2>&1
check "reproduce-runs: a corrected render runs with --bias-correction, done or not applicable" \
  bash -c "grep -q -- '--bias-correction' $ROOT/conventional-corrected-p2000-n10/seed1.run.json &&
           grep -qE '\"exit\": (0|2),' $ROOT/conventional-corrected-p2000-n10/seed1.run.json"

make -s reproduce-table "${ARGS[@]}" TAG=v PM_ARGS="--rep-every 2" METHODS=precomputed CONV_RUNROOT="$ROOT" \
  PHOTONS=4000 NNS=10 SEEDS=2 > "$TMP/variant.log" 2>&1
check "reproduce-table: a variant (TAG, PM_ARGS) in its own directory, compared with CONV_RUNROOT's conventional renders" pycheck '
r = pd.read_csv(f"{R}/table1/runs-v.csv")
assert sorted(set(r["role"])) == ["comparison", "grid"] and (r.loc[r["role"] == "grid", "tag"] == "v").all(), r
assert (r.loc[r["role"] == "comparison", "method"] == "conventional").all() and (r["status"] == "ok").all()
assert (r.loc[r["role"] == "grid", "rep_every"] == 2).all() and (r.loc[r["role"] == "grid", "relmse_conv"] > 0).all()
assert all(os.path.isdir(p) for p in r.loc[r["role"] == "grid", "run"].map(os.path.dirname)), r["run"]
assert all("/cornell-32x24-s2-t1-v/" in p for p in r.loc[r["role"] == "grid", "run"])
t = pd.read_csv(f"{R}/table1/table1-v.csv")
assert len(t) == 1 and t["conv_cpu_median_s"].iloc[0] >= 0 and t["ratio_percent"].iloc[0] > 0, t
assert os.path.isfile(f"{R}/table1/equal-error-v.md") and os.path.isfile(f"{R}/table1/table1-v.md")
'
# both estimates: a renderer that takes --bias-correction by dropping it (so
# the corrected images equal the paper's) and refuses it with n = 20
cat > "$TMP/pm2" <<EOF
#!/usr/bin/env bash
args=() corr=0
for a in "\$@"; do if [ "\$a" = --bias-correction ]; then corr=1; else args+=("\$a"); fi; done
if [ \$corr -eq 1 ]; then case " \$* " in *" --nn 20 "*) echo "photonmap: test: no --bias-correction with n=20" >&2; exit 2 ;; esac; fi
exec "$REAL_PM" "\${args[@]}"
EOF
chmod +x "$TMP/pm2"
make -s reproduce-table "${ARGS[@]}" PM="$TMP/pm2" RESULTS="$TMP/r2" "ESTIMATES=paper corrected" PHOTONS=2000 SEEDS=2 \
  > "$TMP/est.log" 2>&1
check "reproduce-table: both estimates, the corrected columns with the suffix _corrected" pycheck '
R = R.replace("/results", "/r2")
t = pd.read_csv(f"{R}/table1/table1.csv")
need = [c + "_corrected" for c in ("relmse_ref_mean", "relmse_ref_ci95", "bias_ref", "variance_ref", "relmse_conv_mean",
                                   "relmse_conv_ci95", "total_median_s")]
assert not [c for c in need if c not in t.columns], t.columns
a, b = t[t.nn == 10], t[t.nn == 20]
assert len(a) == 2 and np.allclose(a.relmse_ref_mean_corrected, a.relmse_ref_mean, rtol=1e-9), t
assert np.allclose(a.bias_ref_corrected, a.bias_ref, rtol=1e-9) and b.relmse_ref_mean_corrected.isna().all()
assert (b.seeds_refused_corrected == 2).all() and (b.seeds == 2).all()
r = pd.read_csv(f"{R}/table1/runs.csv")
assert len(r) == 16 and (r.status == "refused").sum() == 4
md = open(f"{R}/table1/table1.md").read()
assert "## Error against the reference: corrected estimate" in md and "no --bias-correction with n=20" in md
assert "corrected vs paper estimate, conventional" in md and "## corrected estimate" in open(f"{R}/table1/equal-error.md").read()
'

make -s resolution "PHOTONS=2000 4000" "NNS=10 20" ESTIMATES=paper RESULTS="$R" BOOTSTRAP=200 "EE_TARGETS=0.1 0.05" \
  PM="$PM" SEEDS=2 RES_SIZES="16x12 32x24" CONV_REF_PHOTONS=5000 CONV_REF_NN=20 \
  RES_TARGETS="1 0.000001" > "$TMP/res.log" 2>&1
check "resolution: table with one row per target and a column per size" \
  bash -c "grep -q '^| 1 | [a-z]*\./paper, P_e=[24]k, n=[0-9]*: .* | [a-z]*\./paper, P_e=[24]k' $R/resolution/resolution.md &&
           grep -q '^| 1.00e-06 | none in grid | none in grid |$' $R/resolution/resolution.md && [ -s $R/resolution/table-16x12.csv ]"
# the cross-scene study on two scenes, tiny
make -s scenes RESULTS="$TMP/sc" SCENES="scenes/cornell.scene scenes/slabs.scene" SIZE=32x24 PHOTONS=2000 \
  NNS="10 20" SEEDS=2 CONV_REF_PHOTONS=20000 CONV_REF_NN=20 SCENES_CELL=p2000-n20 > "$TMP/sc.log" 2>&1
scenes_ok() {
  [ -s "$TMP/sc/figures/scenes.png" ] && grep -q '^| cornell | ' "$TMP/sc/scenes/scenes.md" && grep -q '^| slabs | ' "$TMP/sc/scenes/scenes.md" &&
  [ -s "$TMP/sc/scenes/table-slabs.csv" ] && [ -s "$TMP/sc/scenes/equal-error-cornell.csv" ] &&
  [ "$(grep -c 'Its own error in relmse: noise [0-9]' "$TMP/sc/scenes/scenes.md")" -eq 2 ] &&
  "${PYTHON:-/usr/bin/python3}" -c 'import pandas as pd, sys; d = pd.read_csv(sys.argv[1]); assert list(d.scene) == ["cornell", "slabs"], d; assert (d.diff_seeds == 2).all(), d' "$TMP/sc/scenes/scenes.csv"
}
check "scenes: one row per scene, its tables, the difference figure" scenes_ok
finish
