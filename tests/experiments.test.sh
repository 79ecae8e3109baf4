#!/usr/bin/env bash
# Experiment drivers (issue 5) end to end on a tiny grid: build/imgmetrics,
# `make reproduce-table` (cells, resume, CSV/Markdown), `make resolution`.
cd "$(dirname "$0")/.." || exit 1
source tests/lib.sh
IM=build/imgmetrics
R=$TMP/results
ARGS=(SIZE=32x24 PHOTONS=2000 "NNS=10 20" REPEATS=1 RESULTS="$R")

# imgmetrics on two tiny renders
$PM render scenes/cornell.scene --width 16 --height 12 --photons 2000 --nn 10 -o "$TMP/a.exr" --quiet
$PM render scenes/cornell.scene --width 16 --height 12 --photons 2000 --nn 10 --method precomputed -o "$TMP/b.exr" --quiet
$PM render scenes/cornell.scene --width 8 --height 6 --photons 2000 --nn 10 -o "$TMP/c.exr" --quiet
check "imgmetrics: identical images give 0 and inf" \
  bash -c "$IM $TMP/a.exr $TMP/a.exr | grep -q '^relmse=0 rmse=0 psnr=inf pixels=192 peak=1$'"
check "imgmetrics: different images give a positive error, CSV form" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --header | awk -F, 'NR==1 && \$0==\"relmse,rmse,psnr,pixels,peak\" {h=1} NR==2 && \$1>0 && \$2>0 && \$3>0 && \$4==192 {v=1} END {exit !(h && v)}'"
check "imgmetrics: --mask restricts the pixels" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --mask $TMP/a.exr | grep -q 'pixels=1[0-9][0-9] '"
check "imgmetrics: --peak max uses the reference maximum" \
  bash -c "$IM $TMP/b.exr $TMP/a.exr --peak max | grep -qv 'peak=1$'"
check "imgmetrics: size mismatch is an error" \
  expect_exit 2 "size mismatch" $IM "$TMP/a.exr" "$TMP/c.exr"
check "imgmetrics: missing file is an error" expect_exit 2 "nonexistent" $IM "$TMP/a.exr" /nonexistent.exr

make -s reproduce-table "${ARGS[@]}" > "$TMP/grid.log" 2>&1
check "reproduce-table: exits 0 and shows progress per cell" \
  bash -c "grep -q 'cell 1/4 conventional P_e=2000 n=10' $TMP/grid.log && grep -q 'cell 4/4 precomputed P_e=2000 n=20' $TMP/grid.log"
check "reproduce-table: CSV has a header and 4 rows" \
  bash -c "[ \$(wc -l < $R/table1.csv) -eq 5 ] && head -n 1 $R/table1.csv | grep -q '^photons,nn,method,.*total_s,.*relmse_conv,psnr_conv,cpu_s,cpu_min_s,cpu_ratio_percent$'"
check "reproduce-table: rows are the grid, times positive, ratio and errors filled" \
  awk -F, 'NR > 1 { n++; key = key $1 "/" $2 "/" $3 " ";
                    if (!($13 > 0) || $16 <= 0 || $4 != 32 || $5 != 24 || $8 != 1) bad = 1
                    if ($3 == "precomputed" && (!($17 > 0) || !($18 > 0) || !($23 > 0) || !($24 > 0))) bad = 1
                    if ($3 == "conventional" && ($18 != "100.0" || $23 != 0)) bad = 1
                    if (NF != 27 || !($25 >= 0) || !($26 >= 0)) bad = 1 }
           END { exit !(n == 4 && !bad && key == "2000/10/conventional 2000/10/precomputed 2000/20/conventional 2000/20/precomputed ") }' "$R/table1.csv"
check "reproduce-table: Markdown has the three tables and the machine" \
  bash -c "grep -q '^| 2000 | 20 | n/a | n/a | n/a | [0-9.e-]* | [0-9.e-]* | [0-9.]* | [0-9.e-]* | [0-9.e-]* | [0-9.na/]* |$' $R/table1.md &&
           grep -q '^| 2000 | 10 | precomputed | [0-9.]* |' $R/table1.md && grep -q 'Machine: .*threads used per render: 1' $R/table1.md &&
           grep -q 'Commit: ' $R/table1.md && grep -q 'n/a: no reference EXR of 32x24' $R/table1.md"
cells=$(ls -d "$R"/cells/32x24-s2-t1/*/ | wc -l)
check "reproduce-table: one directory per cell" test "$cells" -eq 4
make -s reproduce-table "${ARGS[@]}" > "$TMP/grid2.log" 2>&1
check "reproduce-table: a second run reuses every cell" bash -c "! grep -q '^cell ' $TMP/grid2.log && grep -q 'wrote' $TMP/grid2.log"
make -s reproduce-table "${ARGS[@]}" REF="$TMP/ref-missing.exr" > "$TMP/grid3.log" 2>&1
check "reproduce-table: a missing reference named by REF is an error" grep -q "reference .* not found" "$TMP/grid3.log"
rm "$R/cells/32x24-s2-t1/precomputed-p2000-n20/summary-r1.tsv"
make -s reproduce-table "${ARGS[@]}" REF="$R/cells/32x24-s2-t1/conventional-p2000-n20/image.exr" > "$TMP/grid4.log" 2>&1
check "reproduce-table: resumes only the missing cell, errors vs REF filled" \
  bash -c "[ \$(grep -c '^cell .* done' $TMP/grid4.log) -eq 1 ] && grep -q '^2000,20,conventional,.*,0,inf,0,inf,[0-9.]*,[0-9.]*,[0-9.na/]*$' $R/table1.csv"

make -s resolution "${ARGS[@]}" RES_SIZES="16x12 32x24" RES_REF_PHOTONS=5000 RES_REF_NN=20 RES_TARGETS="1 0.000001" > "$TMP/res.log" 2>&1
check "resolution: table with one row per target and a column per size" \
  bash -c "grep -q '^| 1 | [a-z]*\., P_e=2k, n=[0-9]*: .* | [a-z]*\., P_e=2k' $R/resolution.md && grep -q '^| 0.000001 | none in grid | none in grid |$' $R/resolution.md"
finish
