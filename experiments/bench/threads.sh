#!/usr/bin/env bash
# experiments/bench/threads.sh (behind `make bench-threads`): the two-thread
# speed-up of the photon pass and the kd-tree build, measured side by side.
# Renders scenes/cornell.scene, conventional, n = 100, 512x384, at each count
# of THREADS_PHOTONS emitted photons, on 1 and on 2 threads in alternating
# order (1 2, 2 1, ...) THREADS_PAIRS times, and records the renderer's own
# phase timers (time_s from --stats). Writes results/bench/threads.csv, then
# experiments/bench/threads.py writes results/bench/threads.md: per count and
# phase the median of the paired ratios t(1 thread) / t(2 threads) with its
# range over the pairs. Outputs go to temporary names and are renamed.
#
#   threads.sh [BIN]   (BIN: build/photonmap)
set -eu
cd "$(dirname "$0")/../.."
BIN=${1:-build/photonmap}
PHOTONS=${THREADS_PHOTONS:?threads.sh: THREADS_PHOTONS unset (make bench-threads sets it from experiments/config.mk)}
PAIRS=${THREADS_PAIRS:?threads.sh: THREADS_PAIRS unset (make bench-threads sets it from experiments/config.mk)}
PYTHON=${PYTHON:-/usr/bin/python3}
if [ ! -x "$BIN" ]; then
  echo "threads.sh: no renderer at $BIN (run make)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p results/bench
echo "photons_emitted,pair,threads,photons_stored,trace_s,build_s,eye_s,total_s" > "$tmp/threads.csv"
for p in $(echo "$PHOTONS" | tr ',' ' '); do
  for k in $(seq 1 "$PAIRS"); do
    if [ $((k % 2)) -eq 1 ]; then order="1 2"; else order="2 1"; fi
    for t in $order; do
      echo "threads: $p photons, pair $k/$PAIRS, $t thread(s)" >&2
      "$BIN" render scenes/cornell.scene --method conventional --nn 100 --photons "$p" \
        --width 512 --height 384 --threads "$t" --quiet -o "$tmp/x.exr" --stats "$tmp/x.json"
      "$PYTHON" - "$tmp/x.json" "$p" "$k" "$t" >> "$tmp/threads.csv" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); t = d["time_s"]
print(",".join([sys.argv[2], sys.argv[3], sys.argv[4], str(d["photons_stored"]),
                str(t["trace"]), str(t["build"]), str(t["render"]), str(t["total"])]))
PY
    done
  done
done
mv "$tmp/threads.csv" results/bench/threads.csv.tmp && mv results/bench/threads.csv.tmp results/bench/threads.csv
"$PYTHON" experiments/bench/threads.py results/bench/threads.csv > "$tmp/threads.md"
mv "$tmp/threads.md" results/bench/threads.md.tmp && mv results/bench/threads.md.tmp results/bench/threads.md
echo "wrote results/bench/threads.md" >&2
