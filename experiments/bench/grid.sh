#!/usr/bin/env bash
# grid.sh: the paper's whole Table 1 grid once (24 renders: P_e 50k/100k/500k
# x n 10/20/50/100 x both methods, 1024x768, 2x2 samples, one thread, the
# paper's estimate, seed 1, no image written), timed render by render; prints
# one line per render and last the line `make bench` quotes:
#   grid: N s, conventional N s, precomputed N s (CPU N s: ...), every render pinned to CPU C
# where N s are the renderers' own wall-clock totals (time_s.total: with
# --repeats, each render's minimum over its repeats) summed, and CPU the
# user+system seconds of the processes (/usr/bin/time, all repeats).
#   grid.sh [PM]
# Environment: GRID_REPEATS (--repeats of each render, default 3; 1 for
# single runs), GRID_PHOTONS (default "50000 100000 500000"), GRID_WIDTH and
# GRID_HEIGHT (default 1024 and 768): a tiny instance checks the script;
# GRID_CPU (default first: the lowest CPU this script may run on; a number;
# none: unpinned), the CPU every render is pinned to (taskset), as the
# studies pin their timed renders (TIME_CPU, experiments/launch.py): on a
# shared machine the CPUs need not be equally fast.
set -euo pipefail
PM=${1:-build/photonmap}
PYTHON=${PYTHON:-/usr/bin/python3}
REPEATS=${GRID_REPEATS:-3}
PHOTONS=${GRID_PHOTONS:-50000 100000 500000}
WIDTH=${GRID_WIDTH:-1024}
HEIGHT=${GRID_HEIGHT:-768}
. "$(dirname "$0")/../pin.sh"
pin_to "${GRID_CPU:-first}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for p in $PHOTONS; do
  for n in 10 20 50 100; do
    for m in conventional precomputed; do
      "${pin[@]}" /usr/bin/time -f "%U %S" -o "$tmp/t" "$PM" render scenes/cornell.scene --method "$m" --photons "$p" --nn "$n" \
        --width "$WIDTH" --height "$HEIGHT" --threads 1 --repeats "$REPEATS" --quiet --stats "$tmp/s.json"
      "$PYTHON" - "$tmp/s.json" "$tmp/t" "$m" "$p" "$n" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["time_s"]
user, system = (float(x) for x in open(sys.argv[2]).read().split()[-2:])
print(f"{sys.argv[3]} {sys.argv[4]} {sys.argv[5]} {t['total']:.3f} {user + system:.2f} "
      f"{t['trace']:.3f} {t['build']:.3f} {t['precompute']:.3f} {t['render']:.3f}")
PY
    done
  done
done > "$tmp/rows"
cat "$tmp/rows"
"$PYTHON" - "$tmp/rows" "$CPU" <<'PY'
import sys
import pandas as pd
cols = ["method", "photons", "nn", "total_s", "cpu_s", "trace_s", "build_s", "precompute_s", "render_s"]
d = pd.read_csv(sys.argv[1], sep=" ", names=cols)
by = d.groupby("method")
print(f"grid: {d['total_s'].sum():.1f} s, conventional {by['total_s'].sum()['conventional']:.1f} s, "
      f"precomputed {by['total_s'].sum()['precomputed']:.1f} s (CPU {d['cpu_s'].sum():.1f} s: "
      f"conventional {by['cpu_s'].sum()['conventional']:.1f} s, precomputed {by['cpu_s'].sum()['precomputed']:.1f} s), "
      + ("unpinned" if sys.argv[2] == "none" else f"every render pinned to CPU {sys.argv[2]}"))
PY
