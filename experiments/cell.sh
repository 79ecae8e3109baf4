#!/usr/bin/env bash
# cell.sh: one cell of `make reproduce-table` (see experiments/table.mk).
#   cell.sh NAME DIR REPEATS  (settings from the environment: PM SCENE WIDTH
#   HEIGHT SUBPIXELS THREADS_ARG CELL_LIST, and PM_ARGS: extra render options)
# NAME is METHOD-pPHOTONS-nNN. Renders REPEATS times with --stats into
# DIR/rep<i>.json (a repeat whose JSON exists is kept, so an interrupted cell
# resumes and raising REPEATS adds repeats); the first repeat also writes
# DIR/image.exr and DIR/image.png. Each render runs under /usr/bin/time, whose
# user+system CPU seconds go to DIR/rep<i>.cpu: on a shared machine the CPU
# time of a single-threaded run is far less disturbed by other processes than
# its wall time. Then writes DIR/summary-r<REPEATS>.tsv: the median over
# repeats of each phase (wall) time, the spread of the total, and the median
# CPU time (n/a when a repeat has no .cpu file).
set -euo pipefail
name=$1 dir=$2 reps=$3
method=${name%%-*}
rest=${name#*-p}; photons=${rest%%-n*}; nn=${rest#*-n}
PM=${PM:-build/photonmap}

# "cell k/N": the cell's position in the full list make was given.
k=0 i=0
for c in ${CELL_LIST:-$name}; do i=$((i + 1)); [ "$c" = "$name" ] && k=$i; done
label="cell $k/$i $method P_e=$photons n=$nn ${WIDTH}x$HEIGHT"

mkdir -p "$dir"
for r in $(seq 1 "$reps"); do
  json=$dir/rep$r.json
  # a repeat is done when its stats and CPU time exist (and, for the first, the image)
  if [ -s "$json" ] && [ -s "$dir/rep$r.cpu" ] && { [ "$r" -gt 1 ] || [ -s "$dir/image.exr" ]; }; then continue; fi
  img=()
  [ "$r" -eq 1 ] && img=(-o "$dir/image.exr" --png "$dir/image.png")
  /usr/bin/time -f "%U %S" -o "$dir/rep$r.cpu.tmp" "$PM" render "$SCENE" --method "$method" --photons "$photons" --nn "$nn" \
    --width "$WIDTH" --height "$HEIGHT" --subpixels "$SUBPIXELS" --threads "$THREADS_ARG" \
    ${PM_ARGS:-} "${img[@]}" --stats "$json.tmp" --quiet
  mv "$json.tmp" "$json"
  awk '{ printf "%.4f\n", $1 + $2 }' "$dir/rep$r.cpu.tmp" > "$dir/rep$r.cpu" && rm -f "$dir/rep$r.cpu.tmp"
  t=$(sed -n 's/.*"total": *\([0-9.e+-]*\).*/\1/p' "$json")
  echo "$label  rep $r/$reps  total ${t} s, cpu $(cat "$dir/rep$r.cpu") s"
done

# Medians over the repeats of each phase (each column's own median).
for r in $(seq 1 "$reps"); do
  cpu=n/a; [ -s "$dir/rep$r.cpu" ] && cpu=$(cat "$dir/rep$r.cpu")
  awk -v cpu="$cpu" '/"time_s"/ { s = $0; gsub(/[{},:"]/, " ", s); n = split(s, w, " ");
         for (i = 1; i < n; i++) t[w[i]] = w[i + 1]; }
       /"photons_stored"/ { gsub(/[",]/, ""); ps = $2 }
       /"representatives"/ { gsub(/[",]/, ""); rp = $2 }
       END { print t["trace"], t["build"], t["precompute"], t["render"], t["total"], ps, rp, cpu }' "$dir/rep$r.json"
done | awk -v reps="$reps" '
  function median(col,   n, i, j, v, tmp) {
    for (i = 1; i <= NR; i++) v[i] = x[i, col];
    for (i = 2; i <= NR; i++) { tmp = v[i]; for (j = i - 1; j >= 1 && v[j] > tmp; j--) v[j + 1] = v[j]; v[j + 1] = tmp; }
    n = NR; return (n % 2) ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2;
  }
  { for (c = 1; c <= NF; c++) x[NR, c] = $c;
    if (NR == 1 || $5 < lo) lo = $5; if (NR == 1 || $5 > hi) hi = $5;
    if ($8 == "n/a") nocpu = 1; else if (NR == 1 || $8 < clo) clo = $8; }
  END {
    print "trace_s\tbuild_s\tprecompute_s\trender_s\ttotal_s\ttotal_min_s\ttotal_max_s\tphotons_stored\trepresentatives\trepeats\tcpu_s\tcpu_min_s";
    printf "%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%d\t%d\t%d\t%s\t%s\n", median(1), median(2), median(3), median(4), median(5), lo, hi, x[1, 6], x[1, 7], reps,
      (nocpu ? "n/a" : sprintf("%.4f", median(8))), (nocpu ? "n/a" : sprintf("%.4f", clo));
  }' > "$dir/summary-r$reps.tsv.tmp"
mv "$dir/summary-r$reps.tsv.tmp" "$dir/summary-r$reps.tsv"
echo "$label  done: median total $(awk 'NR==2 {print $5}' "$dir/summary-r$reps.tsv") s over $reps"
