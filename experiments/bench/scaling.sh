#!/usr/bin/env bash
# experiments/bench/scaling.sh (behind `make bench-scaling`, which `make
# bench` runs too): how each phase's cost grows with the work. Renders
# scenes/cornell.scene, conventional and precomputed, n = 100, 512x384, on
# SCALING_THREADS threads, at each count of emitted photons in
# SCALING_PHOTONS (space- or comma-separated; defaults in
# experiments/config.mk), and records the renderer's own
# phase times (time_s from --stats: trace, build, precompute, eye pass, each
# the minimum over SCALING_REPEATS repeats in the render's process) and
# the peak resident set (/usr/bin/time -f %M) per stored photon of a second
# process of the same render with --repeats 1: repeats keep the memory they
# free for the next (mem_keep), so the timed process's peak is not what one
# render needs. Writes
# results/bench/scaling.csv, then experiments/bench/scaling.py fits each
# phase's slope of log(cost) against log(emitted photons) and writes
# results/bench/scaling.md and results/figures/bench-scaling.png.
#
#   scaling.sh [BIN]   (BIN: build/photonmap)
#
# Every output is written to a temporary name and renamed: a killed run
# leaves the previous results, never a partial table.
set -eu
cd "$(dirname "$0")/../.."
BIN=${1:-build/photonmap}
PHOTONS=${SCALING_PHOTONS:?scaling.sh: SCALING_PHOTONS unset (make bench-scaling sets it from experiments/config.mk)}
THREADS=${SCALING_THREADS:?scaling.sh: SCALING_THREADS unset (make bench-scaling sets it from experiments/config.mk)}
REPEATS=${SCALING_REPEATS:?scaling.sh: SCALING_REPEATS unset (make bench-scaling sets it from experiments/config.mk)}
PYTHON=${PYTHON:-/usr/bin/python3}
TIME=/usr/bin/time
CSV=results/bench/scaling.csv
MD=results/bench/scaling.md
PNG=results/figures/bench-scaling.png
if [ ! -x "$BIN" ]; then
  echo "scaling.sh: no renderer at $BIN (run make)" >&2
  exit 1
fi
if [ ! -x "$TIME" ]; then
  echo "scaling.sh: $TIME is missing (apt-get install time): the peak memory needs it" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p results/bench results/figures

echo "method,photons_emitted,photons_stored,representatives,threads,repeats,trace_s,build_s,precompute_s,eye_s,total_s,peak_rss_bytes,bytes_per_stored" > "$tmp/scaling.csv"
for method in conventional precomputed; do
  for p in ${PHOTONS//,/ }; do
    echo "scaling: $method, $p photons" >&2
    "$BIN" render scenes/cornell.scene --method "$method" --nn 100 --photons "$p" \
      --width 512 --height 384 --threads "$THREADS" --repeats "$REPEATS" --quiet --stats "$tmp/stats.json"
    "$TIME" -f %M -o "$tmp/rss" "$BIN" render scenes/cornell.scene --method "$method" --nn 100 --photons "$p" \
      --width 512 --height 384 --threads "$THREADS" --repeats 1 --quiet --no-output
    "$PYTHON" - "$tmp/stats.json" "$tmp/rss" "$method" "$THREADS" >> "$tmp/scaling.csv" <<'EOF'
import json, sys
st = json.load(open(sys.argv[1]))
# /usr/bin/time -f %M: the peak resident set in KiB, on the file's last line
rss = int(open(sys.argv[2]).read().split()[-1]) * 1024
t = st["time_s"]
stored = st["photons_stored"]
print(",".join(str(v) for v in (
    sys.argv[3], st["photons_emitted"], stored, st["representatives"], sys.argv[4], st["repeats"],
    t["trace"], t["build"], t["precompute"], t["render"], t["total"], rss,
    "%.3f" % (rss / stored) if stored else "")))
EOF
  done
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
"$PYTHON" experiments/bench/scaling.py "$tmp/scaling.csv" --md "$tmp/scaling.md" --png "$tmp/bench-scaling.png" \
  --load "$load" --commit "$(git rev-parse --short HEAD 2> /dev/null || echo '?')" --threads "$THREADS"
# copied beside their final names, then renamed (a rename within one directory)
for f in "$tmp/scaling.csv:$CSV" "$tmp/scaling.md:$MD" "$tmp/bench-scaling.png:$PNG"; do
  cp "${f%%:*}" "${f#*:}.tmp"
done
for dst in "$CSV" "$MD" "$PNG"; do
  mv "$dst.tmp" "$dst"
done
echo "scaling: wrote $CSV, $MD, $PNG" >&2
