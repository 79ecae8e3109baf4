#!/usr/bin/env bash
# figures.sh: the driver behind `make figures` (experiments/figures.mk).
# Composites with oiiotool, plots with gnuplot (pngcairo); no image code here.
# Images: the paper estimate's renders of seed FIG_SEED under RUNROOT; the
# table's columns are read by name. Reference image: the POV-Ray render of
# FIG_SIZE in reference/ (experiments/findref.sh), else our high-photon
# render from `make resolution` (REFHIGH).
set -euo pipefail
: "${RESULTS:?}" "${RUNROOT:?}" "${FIG_SIZE:?}" "${TABLE_CSV:?}" "${FIG_SEED:?}"
PYTHON=${PYTHON:-/usr/bin/python3}
OUT=$RESULTS/figures
FONT=${FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}
TILE=${TILE:-288x216}
ERR_SCALE=${ERR_SCALE:-10}   # false colour: |error| (luminance) x ERR_SCALE, 1 = top of the map
tmp=$(mktemp -d "${TMPDIR:-/tmp}/pm-fig.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$OUT"
[ -s "$TABLE_CSV" ] || { echo "figures: $TABLE_CSV missing: run make reproduce-table first" >&2; exit 1; }

ref=$(bash experiments/findref.sh "$FIG_SIZE")
if [ -n "$ref" ]; then reflabel="POV-Ray reference"
else
  ref=${REFHIGH:-}
  reflabel="ours, P_e=$(( ${RES_REF_PHOTONS:-2000000} / 1000 ))k n=${RES_REF_NN:-200}"
  [ -s "$ref" ] || { ref=""; reflabel=""; echo "figures: no reference image of $FIG_SIZE: reference column left out" >&2; }
fi
txt() { echo "--text:x=8:y=22:size=16:color=1,1,1:shadow=2:font=$FONT"; }
tile() { # EXR LABEL OUT.png: sRGB 8-bit tile with a label
  oiiotool "$1" --resize "$TILE" --colorconvert linear sRGB --clamp:min=0:max=1 "$(txt)" "$2" -d uint8 -o "$3"
}
errtile() { # EXR REF LABEL OUT.png: false-colour |EXR - REF| (luminance)
  oiiotool "$1" "$2" --absdiff --chsum:weight=0.2126,0.7152,0.0722 --mulc "$ERR_SCALE" --clamp:min=0:max=1 \
    --colormap inferno --resize "$TILE" "$(txt)" "$3" -d uint8 -o "$4"
}
cell() { echo "$RUNROOT/$1-paper-p$2-n$3/seed$FIG_SEED.exr"; }
# A table CSV's columns by name, one line per row, "n/a" for empty values:
# photons nn method cpu_median_s total_median_s relmse_ref_mean paper_s
tablecols() {
  "$PYTHON" - "$1" <<'PY'
import csv, sys
need = ["photons", "nn", "method", "cpu_median_s", "total_median_s", "relmse_ref_mean", "paper_s"]
with open(sys.argv[1], newline="", encoding="utf-8") as f:
    rows = csv.DictReader(f)
    missing = [c for c in need if c not in (rows.fieldnames or [])]
    if missing:
        sys.exit(f"figures: {sys.argv[1]}: no column(s) {', '.join(missing)}")
    for r in rows:
        print(" ".join(r[c] if r[c] else "n/a" for c in need))
PY
}
tablecols "$TABLE_CSV" > "$tmp/table.txt"

# ---- Figure 3 (+ reference column) and the error maps against the reference
fig3=() errs=()
for pn in "50000 10" "100000 100" "500000 100"; do
  set -- $pn; k=$(( $1 / 1000 ))k
  for m in conventional precomputed; do
    f=$(cell $m "$1" "$2"); [ -s "$f" ] || { echo "figures: $f missing: run make reproduce-table" >&2; exit 1; }
    short=$([ $m = conventional ] && echo conventional || echo precomputed)
    tile "$f" "$short  P_e=$k n=$2" "$tmp/$m-$1-$2.png"; fig3+=("$tmp/$m-$1-$2.png")
    [ -n "$ref" ] && { errtile "$f" "$ref" "|$(echo $short | cut -c1-4). - ref|  P_e=$k n=$2" "$tmp/err-$m-$1-$2.png"; errs+=("$tmp/err-$m-$1-$2.png"); }
  done
  if [ -n "$ref" ]; then tile "$ref" "$reflabel" "$tmp/ref-$1.png"; fig3+=("$tmp/ref-$1.png"); fi
done
cols=$([ -n "$ref" ] && echo 3 || echo 2)
oiiotool "${fig3[@]}" --mosaic:pad=4 "${cols}x3" -d uint8 -o "$OUT/fig3.png"
echo "wrote $OUT/fig3.png"
if [ -n "$ref" ]; then
  oiiotool "${errs[@]}" --mosaic:pad=4 2x3 -d uint8 -o "$tmp/errs.png"
  # a legend strip under the maps: the colour map from 0 to 1/ERR_SCALE
  w=$(oiiotool "$tmp/errs.png" --echo "{TOP.width}" | tail -n 1)
  h=$(oiiotool "$tmp/errs.png" --echo "{TOP.height}" | tail -n 1)
  top=$(awk -v s="$ERR_SCALE" 'BEGIN { print 1 / s }')
  oiiotool --pattern fill:left=0:right=1 "${w}x36" 1 --colormap inferno \
    "--text:x=8:y=26:size=18:color=1,1,1:shadow=2:font=$FONT" "0" \
    "--text:x=$((w / 2 - 200)):y=26:size=16:color=1,1,1:shadow=2:font=$FONT" "|luminance error| vs $reflabel" \
    "--text:x=$((w - 50)):y=26:size=18:color=0,0,0:font=$FONT" "$top" -d uint8 -o "$tmp/legend.png"
  # (--paste puts the image below the top of the stack onto the top one)
  oiiotool "$tmp/errs.png" --create "${w}x$((h + 36))" 3 --paste +0+0 -o "$tmp/canvas.png"
  oiiotool "$tmp/legend.png" "$tmp/canvas.png" --paste "+0+$h" -d uint8 -o "$OUT/fig3-errors.png"
  echo "wrote $OUT/fig3-errors.png"
fi

# ---- Crops: the 32x32 blocks where precomputed and conventional differ most (relative), (50k, 10)
a=$(cell conventional 50000 10) b=$(cell precomputed 50000 10)
W=${FIG_SIZE%x*} H=${FIG_SIZE#*x} bw=32
# relative difference |a-b|/(a+b+0.1), so that bright (display-saturated) regions do not win
oiiotool "$a" "$b" --absdiff "$a" "$b" --add --addc 0.1 --div --chsum:weight=0.2126,0.7152,0.0722 \
  --resize "$((W / bw))x$((H / bw))" -o "$tmp/blocks.exr"
oiiotool --dumpdata "$tmp/blocks.exr" | sed -n 's/.*Pixel (\([0-9]*\), \([0-9]*\)): \([0-9.e+-]*\).*/\3 \1 \2/p' | sort -gr |
  awk -v bw=$bw -v W="$W" -v H="$H" '!done { # three blocks at least 4 blocks apart
      ok = 1; for (i = 1; i <= n; i++) if ((x[i] - $2)^2 + (y[i] - $3)^2 < 16) ok = 0
      if (ok) { n++; x[n] = $2; y[n] = $3; cx = $2 * bw + bw / 2 - 64; cy = $3 * bw + bw / 2 - 64
                if (cx < 0) cx = 0; if (cy < 0) cy = 0; if (cx > W - 128) cx = W - 128; if (cy > H - 128) cy = H - 128
                print cx, cy }
      if (n == 3) done = 1 }' > "$tmp/crops.txt" # (reads all: an early exit kills sort by SIGPIPE)
crops=()
i=0
while read -r cx cy; do
  i=$((i + 1))
  for src in "conventional:$a" "precomputed:$b" ${ref:+"ref:$ref"}; do
    name=${src%%:*} f=${src#*:}
    label=$([ "$name" = ref ] && echo "$reflabel" || echo "$name")
    oiiotool "$f" --cut "128x128+$cx+$cy" --resize:filter=box 256x256 --colorconvert linear sRGB --clamp:min=0:max=1 \
      "--text:x=6:y=20:size=14:color=1,1,1:shadow=2:font=$FONT" "$label ($cx,$cy)" -d uint8 -o "$tmp/crop$i-$name.png"
    crops+=("$tmp/crop$i-$name.png")
  done
done < "$tmp/crops.txt"
oiiotool "${crops[@]}" --mosaic:pad=4 "$([ -n "$ref" ] && echo 3 || echo 2)x$i" -d uint8 -o "$OUT/crops.png"
echo "wrote $OUT/crops.png (P_e=50k n=10: the $i 128x128 regions where the methods differ most, 2x)"

# ---- Plots (gnuplot, pngcairo)
# Time axis: the median CPU time of the process when every cell has one
# (robust on a shared machine), else the median wall-clock total.
if awk '$4 == "n/a" { f = 1 } END { exit f }' "$tmp/table.txt"; then
  tlabel="median CPU time, s (1 thread)"; tcol=4
else tlabel="median wall-clock total, s (1 thread)"; tcol=5; fi
# Error source for the trade-off: mean relMSE vs the reference in the table;
# if that column is n/a, the FIG_SIZE grid of `make resolution` (vs our own
# high-photon render).
errtxt=$tmp/table.txt errlabel="mean relMSE vs POV-Ray reference"
if ! awk '$6 != "n/a" { f = 1 } END { exit !f }' "$errtxt"; then
  errtxt=$tmp/res.txt
  [ -s "$RESULTS/resolution/table-$FIG_SIZE.csv" ] && tablecols "$RESULTS/resolution/table-$FIG_SIZE.csv" > "$errtxt"
  errlabel="mean relMSE vs our P_e=$(( ${RES_REF_PHOTONS:-2000000} / 1000 ))k n=${RES_REF_NN:-200} render"
fi
if [ -s "$errtxt" ] && awk '$6 != "n/a" { f = 1 } END { exit !f }' "$errtxt"; then
  awk -v c=$tcol '$6 != "n/a" && $c != "n/a" { print $c, $6, $3, $1 / 1000 "k/" $2 }' "$errtxt" > "$tmp/pts.txt"
  # Pareto front: no other cell is both faster and more accurate
  sort -g "$tmp/pts.txt" | awk 'NR == 1 || $2 < best { best = $2; print }' > "$tmp/front.txt"
  grep ' conventional ' "$tmp/pts.txt" > "$tmp/conv.txt" || true
  grep ' precomputed ' "$tmp/pts.txt" > "$tmp/prec.txt" || true
  gnuplot <<GP
set terminal pngcairo size 900,620 font "DejaVu Sans,11"
set output "$OUT/tradeoff.png"
set title "Speed-accuracy trade-off, $FIG_SIZE, every cell of the grid (label: P_e/n)"
set xlabel "$tlabel"; set ylabel "$errlabel"
set logscale xy; set grid; set key top right
plot "$tmp/front.txt" using 1:2 with steps lw 2 lc rgb "#999999" title "Pareto front", \
     "$tmp/conv.txt" using 1:2 with points pt 7 ps 1.4 lc rgb "#1f77b4" title "conventional", \
     "$tmp/prec.txt" using 1:2 with points pt 9 ps 1.6 lc rgb "#d62728" title "precomputed", \
     "$tmp/front.txt" using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb "black" title "on the front", \
     "$tmp/pts.txt" using 1:2:4 with labels offset 0.6,0.6 left font ",8" notitle
GP
  echo "wrote $OUT/tradeoff.png ($errlabel)"
else
  echo "figures: no error data: tradeoff.png not made (run make resolution)" >&2
fi

# time vs n and time vs P_e: ours (left) beside the paper (right)
awk -v c=$tcol '{ print $1, $2, $3, $c, $7 }' "$tmp/table.txt" > "$tmp/t.txt"
gp_series() { # FILE-FILTER-COLUMN: plot clauses per P_e (or n) and method
  local x=$1 key=$2 vals=$3 ycol=$4 s="" c i=0
  for v in $vals; do
    i=$((i + 1))
    for m in conventional precomputed; do
      c=$([ $m = conventional ] && echo 1 || echo 2)
      s+="\"< awk '\\\$3==\\\"$m\\\" \\&\\& \\\$$key==$v && \\\$$ycol!=\\\"n/a\\\"' $tmp/t.txt | sort -g -k$x\" using $x:$ycol with linespoints dt $c lw 2 lc $i title \"$m, $(if [ "$key" = 1 ]; then echo "P_e=$((v / 1000))k"; else echo "n=$v"; fi)\", "
    done
  done
  echo "${s%, }"
}
ps=$(awk '{ print $1 }' "$tmp/t.txt" | sort -gu | tr '\n' ' ')
ns=$(awk '{ print $2 }' "$tmp/t.txt" | sort -gu | tr '\n' ' ')
gnuplot <<GP
set terminal pngcairo size 1200,500 font "DejaVu Sans,10"
set output "$OUT/time-vs-n.png"
set multiplot layout 1,2 title "Total time vs n (solid: conventional, dashed: precomputed), $FIG_SIZE"
set xlabel "n (nearest photons)"; set ylabel "$tlabel"; set grid; set key top left font ",8"
set title "ours"; set ylabel "$tlabel"
plot $(gp_series 2 1 "$ps" 4)
set title "paper (Core2 Duo 2.93 GHz)"; set ylabel "total time, s (paper, Table 1)"
plot $(gp_series 2 1 "$ps" 5)
unset multiplot
set output "$OUT/time-vs-photons.png"
set multiplot layout 1,2 title "Total time vs emitted photons P_e (solid: conventional, dashed: precomputed), $FIG_SIZE"
set xlabel "P_e (emitted photons)"; set logscale x
set title "ours"; set ylabel "$tlabel"
plot $(gp_series 1 2 "$ns" 4)
set title "paper (Core2 Duo 2.93 GHz)"; set ylabel "total time, s (paper, Table 1)"
plot $(gp_series 1 2 "$ns" 5)
unset multiplot
GP
echo "wrote $OUT/time-vs-n.png $OUT/time-vs-photons.png"
