#!/usr/bin/env bash
# figures.test.sh: `make figures`, `make rep-study` and `make caustic` end to
# end on a tiny grid (64x48, 2,000-4,000 photons, n = 10 and 20, 2 seeds,
# both estimates): every PNG and Markdown file they promise is written, the
# PNGs are images with content, the Markdown has its sections and no nan,
# and the errors a user meets (no table yet, a Figure 3 cell outside the
# grid, an unknown rule) say what is wrong and exit non-zero.
cd "$(dirname "$0")/.." || exit 1
source tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}
R=$TMP/results
ARGS=(SIZE=64x48 "PHOTONS=2000 4000" "NNS=10 20" SEEDS=2 RESULTS="$R" PM="$PM" REF="$TMP/ref.exr" BOOTSTRAP=100
      "FIG3_CELLS=2000:10 4000:20 2000:20 4000:10" FIG3_PAPER_CELLS=2 FIG2_PHOTONS=4000 FIG2_NN=10
      "REP_RULES=every2 count500 shared")
# the caustic study: its scene and size, the same knobs
CARGS=(SIZE=32x24 "PHOTONS=2000 4000" "NNS=10 20" SEEDS=2 RESULTS="$R" PM="$PM" REF="$TMP/caustic-ref.exr" BOOTSTRAP=100
       "FIG3_CELLS=2000:10 4000:20 2000:20 4000:10")

# references of the tiny sizes: high-photon renders
$PM render scenes/cornell.scene --width 64 --height 48 --photons 40000 --nn 100 -o "$TMP/ref.exr" --quiet
CS=scenes/caustic.scene
$PM render "$CS" --width 32 --height 24 --photons 40000 --nn 100 -o "$TMP/caustic-ref.exr" --quiet

# pngs_ok FILE...: each is a PNG wider than 300 pixels whose pixels are not all one colour
pngs_ok() {
  "$PY" - "$@" <<'PY'
import sys
import matplotlib.image as mpimg
for path in sys.argv[1:]:
    img = mpimg.imread(path)
    assert img.ndim == 3 and img.shape[1] > 300 and img.shape[0] > 200, (path, img.shape)
    assert float(img[..., :3].std()) > 0.01, (path, "blank")
print("ok")
PY
}

make -s figures "${ARGS[@]}" > "$TMP/nofig.log" 2>&1; rc=$?
check "figures before reproduce-table: exit non-zero, names the missing table" \
  bash -c "[ $rc -ne 0 ] && grep -q 'table1.csv: missing' $TMP/nofig.log"

make -s reproduce-table "${ARGS[@]}" > "$TMP/grid.log" 2>&1
make -s figures "${ARGS[@]}" > "$TMP/fig.log" 2>&1; rc=$?
check "figures: exit 0, every PNG written" \
  bash -c "[ $rc -eq 0 ] || { cat $TMP/fig.log; exit 1; }; for f in glance fig3 fig3-errors fig2 tradeoff ratio-vs-n phases; do
             [ -s $R/figures/\$f.png ] || { echo \"\$f.png missing\"; exit 1; }; done"
check "figures: the PNGs are images with content" pngs_ok "$R"/figures/{glance,fig3,fig3-errors,fig2,tradeoff,ratio-vs-n,phases}.png
check "figures: Figure 2's render dumped its representatives (one line each)" \
  bash -c "b=$R/runs/fig2-cornell-64x48-s2/precomputed-paper-p4000-n10/seed1 &&
           reps=\$(sed -n 's/.*\"representatives\": \\([0-9]*\\),/\\1/p' \$b.stats.json) &&
           [ \$((\$(wc -l < \$b.reps.csv) - 1)) -eq \"\$reps\" ] && [ -s \$b.exr ] && [ -s \$b.run.json ]"
check "figures: no temporary file left" bash -c "! ls $R/figures/ | grep -q tmp"

make -s figures "${ARGS[@]}" "FIG3_CELLS=2000:10 8000:10" > "$TMP/badcell.log" 2>&1; rc=$?
check "figures: a Figure 3 cell outside the grid: exit non-zero naming it" \
  bash -c "[ $rc -ne 0 ] && grep -q 'P_e=8000, n=10' $TMP/badcell.log"

make -s rep-study "${ARGS[@]}" > "$TMP/rep.log" 2>&1; rc=$?
check "rep-study: exit 0, the report, its CSVs and its figure" \
  bash -c "[ $rc -eq 0 ] || { tail -n 20 $TMP/rep.log; exit 1; }; [ -s $R/rep-study/rep-study.md ] && [ -s $R/rep-study/rep-study.csv ] &&
           [ -s $R/rep-study/rep-study-cells.csv ] && [ -s $R/figures/rep-study.png ]"
check "rep-study: each rule rendered as its own variant (precomputed, paper estimate)" \
  bash -c "for t in every2 count500 shared; do [ -s $R/rep-study/runs-rep-\$t.csv ] && [ -s $R/rep-study/table1-rep-\$t.md ] || exit 1; done &&
           ! ls -d $R/runs/cornell-64x48-s2-t1-rep-every2/conventional-* 2>/dev/null | grep -q . &&
           ls -d $R/runs/cornell-64x48-s2-t1-rep-shared/precomputed-paper-p2000-n10 >/dev/null"
check "rep-study: the PNG has content" pngs_ok "$R/figures/rep-study.png"
check "rep-study.md: the sections, a row per rule, the paper's slopes, no nan" \
  bash -c "grep -q '^## Which rule reproduces the paper' $R/rep-study/rep-study.md && grep -q '^| \*\*paper\*\* ' $R/rep-study/rep-study.md &&
           grep -q '^| every 4th (default) |' $R/rep-study/rep-study.md && grep -q '^| every 2nd |' $R/rep-study/rep-study.md &&
           grep -q '^| count 500 |' $R/rep-study/rep-study.md && grep -q '^| shared tree |' $R/rep-study/rep-study.md &&
           grep -q 'Note:.* 64x48' $R/rep-study/rep-study.md && ! grep -qiw 'nan' $R/rep-study/rep-study.md"
check "rep-study.csv: a fit per rule and P_e, with the paper's slope ratio by name" "$PY" -c "
import pandas as pd
f = pd.read_csv('$R/rep-study/rep-study.csv')
need = ['rule', 'photons', 'reps', 'b_prec', 'b_prec_half', 'b_conv', 'slope_ratio', 'slope_ratio_lo', 'slope_ratio_hi',
        'paper_slope_ratio', 'z']
assert not [c for c in need if c not in f.columns], f.columns
assert len(f) == 8 and sorted(set(f.rule)) == ['count500', 'every2', 'every4', 'shared'], f[['rule', 'photons']]
c = f[f.rule == 'count500']
assert (c.reps == 500).all(), c.reps
assert f.paper_slope_ratio.isna().all()  # the tiny grid's photon counts are not the paper's
"
check "rep-study-rules.csv: a test per rule by name; no paper P_e in the tiny grid, so no test and no Holm" "$PY" -c "
import pandas as pd
r = pd.read_csv('$R/rep-study/rep-study-rules.csv')
need = ['rule', 'fitted', 'chi2', 'dof', 'p_value', 'p_holm', 'verdict']
assert not [c for c in need if c not in r.columns], r.columns
assert sorted(r.rule) == ['count500', 'every2', 'every4', 'shared'], r.rule
assert (r.verdict == 'no test').all() and r.p_holm.isna().all(), r
assert r.set_index('rule').loc['count500', 'fitted'] == 1 and r.set_index('rule').loc['every2', 'fitted'] == 0
"
make -s rep-study "${ARGS[@]}" REP_RULES=every0 > "$TMP/badrule.log" 2>&1; rc=$?
check "rep-study: an unknown rule is refused naming it" \
  bash -c "[ $rc -ne 0 ] && grep -q \"rule 'every0'\" $TMP/badrule.log"

make -s caustic "${CARGS[@]}" > "$TMP/caustic.log" 2>&1; rc=$?
check "caustic: exit 0, report, CSV, its own runs and the figure" \
  bash -c "[ $rc -eq 0 ] || { tail -n 20 $TMP/caustic.log; exit 1; }; [ -s $R/caustic/caustic.md ] && [ -s $R/caustic/caustic.csv ] &&
           [ -s $R/caustic/caustic-runs.csv ] && [ -s $R/figures/caustic.png ] && ls -d $R/runs/caustic-32x24-s2-t1 >/dev/null"
check "caustic: the PNG has content" pngs_ok "$R/figures/caustic.png"
check "caustic.md: the window, both estimates, a row per cell, no nan" \
  bash -c "grep -q 'Caustic window: \`24x20+52+76\` at 128x96' $R/caustic/caustic.md && grep -q '6x5 pixels' $R/caustic/caustic.md &&
           grep -q '^## paper estimate' $R/caustic/caustic.md && grep -q '^## corrected estimate' $R/caustic/caustic.md &&
           [ \$(grep -c '^| [24]k | [12]0 | 2 |' $R/caustic/caustic.md) -eq 8 ] && ! grep -qiw 'nan' $R/caustic/caustic.md"
check "caustic.csv: window metrics by name, the conventional against itself is 0" "$PY" -c "
import pandas as pd
c = pd.read_csv('$R/caustic/caustic.csv')
need = ['estimate', 'photons', 'nn', 'method', 'seeds', 'win_relmse_ref_mean', 'win_relmse_ref_ci95',
        'win_peak_ratio_mean', 'win_relmse_conv_mean', 'relmse_ref_mean']
assert not [k for k in need if k not in c.columns], c.columns
assert len(c) == 16 and (c.seeds == 2).all()
conv = c[c.method == 'conventional']
assert (conv.win_relmse_conv_mean == 0).all() and (c[c.method == 'precomputed'].win_relmse_conv_mean > 0).all()
assert (c.win_relmse_ref_mean > 0).all() and (c.win_peak_ratio_mean > 0).all()
"
finish
