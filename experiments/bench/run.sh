#!/usr/bin/env bash
# experiments/bench/run.sh (behind `make bench`): times the paper's whole grid
# (experiments/bench/grid.sh: the "grid:" line, each render's minimum over
# GRID_REPEATS repeats, default 3), runs build/bench/bench
# for the throughput tables, the same under callgrind for instructions per
# query (beside those of the kd-tree before, icount-before.csv), a perf
# profile of the renders, and the heaviest cells of the paper at full
# resolution under /usr/bin/time -v; writes results/bench/bench.md (tables from
# files by report.py), with the kNN against FLANN, scipy's cKDTree and
# nanoflann (bench --peers, k = BENCH_PEER_KS), and the scaling and
# two-thread sections (scaling.sh, threads.sh: SCALING_PHOTONS,
# SCALING_THREADS, THREADS_PHOTONS, THREADS_PAIRS from experiments/config.mk
# through make). BENCH_REPS (5) runs per throughput cell, BENCH_HEAVY_REPS (3)
# per heavy cell. The peers section also goes alone to results/bench/peers.md,
# with its raw timings in peers.csv (one row per answer and run: who, order,
# pe, stored, k, queries, rep, seconds; the neighbour-set checks as rep =
# check), as --peers writes them; README's summary is computed from peers.csv. Last, final gathering
# at full size: cornell 1024x768, --gather 32, P_e = 100k, n = 50, the
# precomputed method, one thread (pbrt-v2's radiance-photon setting), its
# minimum over BENCH_GATHER_REPEATS (2) repeats and the process's CPU
# seconds per repeat.
#
#   run.sh --quick   (`make bench-quick`, about a minute): only the peers
#                    table at k = 10 and 100, 3 runs a cell, on stdout;
#                    results/bench/bench.md is left as it is.
#   run.sh --peers   (`make bench-peers`): only the peers section, k =
#                    BENCH_PEER_KS (1, 10, 100), BENCH_REPS runs a cell, to results/bench/peers.md
#                    and its raw timings to peers.csv (the same section as in bench.md, for a loaded machine
#                    where the whole benchmark does not fit).
set -eu
cd "$(dirname "$0")/../.."
QUICK=0
PEERS_ONLY=0
if [ "${1:-}" = "--quick" ]; then QUICK=1; fi
if [ "${1:-}" = "--peers" ]; then PEERS_ONLY=1; fi
REPS=${BENCH_REPS:-5}
PEER_KS=${BENCH_PEER_KS:-1,10,100}
HREPS=${BENCH_HEAVY_REPS:-3}
GREPS=${BENCH_GATHER_REPEATS:-2}
# the peers' map (photons emitted) and extra bench arguments: a tiny
# instance (BENCH_PEER_PHOTONS=20000 BENCH_PEER_ARGS="--qw 64 --qh 48") checks the pipeline
PEER_PHOTONS=${BENCH_PEER_PHOTONS:-500000}
PEER_ARGS=${BENCH_PEER_ARGS:-}
OUT=results/bench/bench.md
BIN=build/bench/bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p results/bench

PYTHON=${PYTHON:-/usr/bin/python3}
# BENCH_CPU (default first: the lowest CPU this script may run on; a number;
# none): the CPU every one-thread measurement runs pinned to (taskset), as
# the studies pin their timed renders (TIME_CPU) and grid.sh its renders;
# the scaling and two-thread sections run on every CPU
. "experiments/pin.sh"
pin_to "${BENCH_CPU:-first}"
where=$([ "$CPU" = none ] && echo "unpinned" || echo "pinned to CPU $CPU")

peers() { # reps ks: the peers table (Markdown) on stdout
  mkdir -p "$tmp/peers"
  # shellcheck disable=SC2086
  "${pin[@]}" "$BIN" --peers "$tmp/peers" --python "$PYTHON" --sizes "$PEER_PHOTONS" --ks "$2" --reps "$1" $PEER_ARGS > "$tmp/peers.csv"
  "$PYTHON" experiments/bench/report.py peers "$tmp/peers.csv"
}
peers_section() { # the Markdown section of the kNN against the peers ($tmp/peers.md, $load_peers)
  echo "## kNN against the peers: FLANN, scipy's cKDTree, nanoflann (one thread, the map of $PEER_PHOTONS photons emitted)"
  echo
  echo "The same points (the map's, in its frame) on two query streams: \`tiles\`, the first diffuse hits"
  echo "through the pixel centres of a 320x240 view in 16x16-tile order; \`subpixels\`, the eye pass's own stream: the"
  echo "four subpixel samples of each pixel of a 160x120 view (the same points), in its order: tile by tile, pixel by pixel,"
  echo "subpixel rows, so that four queries in a row lie a fraction of a photon spacing apart. Radius cap"
  echo "0.05 x the photons' bounding-box diagonal, leaf size 12 for every tree. Ours: \`kd_query_knn\` with its"
  echo "state carried from query to query. FLANN 1.9: \`KDTreeSingleIndex<L2_Simple<float>>\`, one call per batch"
  echo "of its documented \`knnSearch\` (the neighbours beyond the cap dropped after) or \`radiusSearch\` with"
  echo "\`max_neighbors = k\`, built without OpenMP. cKDTree (scipy $("$PYTHON" -c 'import scipy; print(scipy.__version__)')): one \`query(k=k,"
  echo "distance_upper_bound=..., workers=1)\` over all queries, in a co-process (experiments/bench/ckdtree.py)"
  echo "driven run by run. nanoflann: \`findNeighbors\` with a capped result set (nano.cpp). Ties: an answer that"
  echo "differs from ours only in points at the other's boundary distance (its k-th, or the cap), within 1e-6"
  echo "relative in double, counts as \"by ties\"; any other difference as wrong, and the bench fails."
  echo "Load average $load_peers before it ran; every process $where."
  echo
  cat "$tmp/peers.md"
}

if [ "$QUICK" = 1 ]; then
  echo "bench: quick: the kNN against the peers, 500k map, tile order and subpixel stream, k = 10 and 100, 3 runs a cell" >&2
  echo "Load average $(cut -d' ' -f1-3 /proc/loadavg) before it ran; commit $(git rev-parse --short HEAD 2> /dev/null || echo '?'); every process $where."
  echo
  peers 3 10,100
  exit 0
fi
# peers_files WHO: results/bench/peers.md (the peers section, WHO naming the
# make target that ran it) and peers.csv (its raw timings), each written under a
# temporary name and renamed
peers_files() {
  {
    echo "# Benchmark: the kNN against the peers"
    echo
    echo "Generated by $1 on $(date -u +%Y-%m-%d), commit"
    echo "\`$(git rev-parse --short HEAD 2> /dev/null || echo '?')\`$(git diff --quiet HEAD -- renderer/kdtree* experiments/bench 2> /dev/null || echo ' + uncommitted kd-tree/bench changes'); CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores. Build: gcc -O2."
    echo
    peers_section
  } > "$tmp/peers-out.md"
  mv "$tmp/peers-out.md" results/bench/peers.md.tmp
  mv results/bench/peers.md.tmp results/bench/peers.md
  cp "$tmp/peers.csv" results/bench/peers.csv.tmp
  mv results/bench/peers.csv.tmp results/bench/peers.csv
  echo "bench: wrote results/bench/peers.md, results/bench/peers.csv" >&2
}

if [ "$PEERS_ONLY" = 1 ]; then
  echo "bench: the kNN against FLANN, cKDTree and nanoflann, k = $PEER_KS ($REPS runs per cell)" >&2
  load_peers=$(cut -d' ' -f1-3 /proc/loadavg)
  peers "$REPS" "$PEER_KS" > "$tmp/peers.md"
  peers_files "experiments/bench/run.sh --peers"
  exit 0
fi

cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
echo "bench: the paper's grid, 24 renders at 1024x768, one thread" >&2
load_grid=$(cut -d' ' -f1-3 /proc/loadavg)
GRID_CPU=$CPU bash experiments/bench/grid.sh build/photonmap > "$tmp/grid.txt"
grid_line=$(tail -n 1 "$tmp/grid.txt")
echo "bench: $grid_line" >&2
echo "bench: throughput tables ($REPS runs per cell)" >&2
"${pin[@]}" "$BIN" --reps "$REPS" > "$tmp/main.md"

echo "bench: the kNN against FLANN, cKDTree and nanoflann ($REPS runs per cell)" >&2
load_peers=$(cut -d' ' -f1-3 /proc/loadavg)
peers "$REPS" "$PEER_KS" > "$tmp/peers.md"

echo "bench: instructions per query (callgrind)" >&2
valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$tmp/cg.out" "$BIN" --icount > /dev/null 2> "$tmp/cg.log"
"$PYTHON" experiments/bench/report.py icount "$tmp/cg.out" experiments/bench/icount-before.csv > "$tmp/icount.md"

echo "bench: profiles (perf)" >&2
profile() { # method nn: a whole render at 1024x768, P_e = 500k, one thread
  if perf record -q -e cpu-clock -o "$tmp/perf.data" build/photonmap render scenes/cornell.scene --photons 500000 \
      --nn "$2" --threads 1 --quiet --no-output --method "$1" > /dev/null 2>&1; then
    perf report -i "$tmp/perf.data" --stdio --no-children --sort symbol 2> /dev/null \
      | grep -E '^ +[0-9.]+%' | head -n 12 | sed 's/^ */    /'
  else
    echo "    (perf record unavailable)"
  fi
}
profile conventional 100 > "$tmp/prof_conv.txt"
profile precomputed 100 > "$tmp/prof_pre.txt"
profile precomputed 10 > "$tmp/prof_pre10.txt"

echo "bench: heavy cells ($HREPS runs each)" >&2
heavy() { # method: one line per run, "method render precompute total rss"
  for r in $(seq "$HREPS"); do
    "${pin[@]}" /usr/bin/time -v build/photonmap render scenes/cornell.scene --method "$1" --photons 500000 --nn 100 \
      --threads 1 --quiet --stats "$tmp/h.json" -o "$tmp/h.exr" 2> "$tmp/h.time" > /dev/null
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$tmp/h.time")
    "$PYTHON" -c 'import json, sys; t = json.load(open(sys.argv[1]))["time_s"]; print(sys.argv[2], t["render"], t["precompute"], t["total"], sys.argv[3])' \
      "$tmp/h.json" "$1" "$rss"
  done
}
{ heavy conventional; heavy precomputed; } > "$tmp/heavy.txt"
"$PYTHON" experiments/bench/report.py heavy "$tmp/heavy.txt" > "$tmp/heavy.md"

echo "bench: final gathering at 1024x768, --gather 32, precomputed ($GREPS repeats)" >&2
load_gather=$(cut -d' ' -f1-3 /proc/loadavg)
"${pin[@]}" /usr/bin/time -f "%U %S" -o "$tmp/g.time" build/photonmap render scenes/cornell.scene --width 1024 --height 768 \
  --gather 32 --photons 100000 --nn 50 --method precomputed --threads 1 --repeats "$GREPS" --quiet \
  --stats "$tmp/g.json" -o "$tmp/g.exr" > /dev/null
"$PYTHON" - "$tmp/g.json" "$tmp/g.time" "$GREPS" "$load_gather" > "$tmp/gather.md" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
t, reps = s["time_s"], int(sys.argv[3])
user, system = (float(x) for x in open(sys.argv[2]).read().split()[-2:])
g = s["gather_work"]
print("cornell 1024x768, 2x2 samples, `--gather 32`, P_e = 100k, n = 50, `--method precomputed`, one thread "
      f"(load average {sys.argv[4]} before it ran):\n")
print("| total (s) | trace | build | precompute | eye pass | CPU s per repeat | gather share of the eye pass | "
      "gather rays | lookups at y | rays cast per gather ray |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
print(f"| {t['total']:.2f} | {t['trace']:.3f} | {t['build']:.3f} | {t['precompute']:.3f} | {t['render']:.2f} | "
      f"{(user + system) / reps:.1f} | {s['gather_time']['share']:.3f} | {g['rays']:,} | {g['lookups']:,} | "
      f"{(g['rays'] + g['specular']) / g['rays']:.3f} |")
print(f"\nTimes: the minimum over {reps} repeats in one process; CPU: the process's user + system seconds "
      f"(/usr/bin/time) over its {reps} repeats, divided by {reps} (the first repeat pays the page faults).")
PY

# The scaling and two-thread sections: their own scripts write their own
# files (results/bench/scaling.md, threads.md); bench.md carries them too,
# headings one level down.
echo "bench: scaling, ${SCALING_PHOTONS:-?} emitted photons (experiments/bench/scaling.sh)" >&2
bash experiments/bench/scaling.sh build/photonmap
echo "bench: two threads against one, ${THREADS_PHOTONS:-?} emitted photons (experiments/bench/threads.sh)" >&2
bash experiments/bench/threads.sh build/photonmap
demote() { sed 's/^#/##/' "$1"; }

{
  echo "# Benchmark: the paper's grid, photon map kNN, representative lookup, eye pass"
  echo
  echo "Generated by \`make bench\` (experiments/bench/run.sh) on $(date -u +%Y-%m-%d), commit"
  echo "\`$(git rev-parse --short HEAD 2> /dev/null || echo '?')\`$(git diff --quiet HEAD -- renderer/kdtree* renderer/render.c experiments/bench 2> /dev/null || echo ' + uncommitted kd-tree/bench changes'); CPU: $cpu, $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) when written. On a shared"
  echo "machine wall times move by +-30%: compare the columns of one row (same process, interleaved)"
  echo "and the instruction counts. Build: gcc -O2 (project default) for both trees."
  echo
  echo "## The paper's whole grid, one thread, each render's minimum over its repeats"
  echo
  echo "24 renders: P_e 50k/100k/500k x n 10/20/50/100 x both methods, 1024x768, 2x2 samples, the paper's estimate,"
  echo "seed 1, no image written (experiments/bench/grid.sh; load average $load_grid before it ran). Per render: method,"
  echo "P_e, n, the renderer's wall-clock total (the minimum over its --repeats), CPU seconds of the process, then trace, build, precompute and eye-pass"
  echo "seconds:"
  echo
  echo '```'
  head -n -1 "$tmp/grid.txt"
  echo '```'
  echo
  echo "**$grid_line**"
  echo
  cat "$tmp/main.md"
  echo
  peers_section
  echo
  echo "## Instructions per kNN query (callgrind, every 9th query of each order, about 8500 per cell)"
  echo
  echo "\"before\": the kd-tree of commit eb9e0ea on the same queries (experiments/bench/icount-before.csv);"
  echo "\"ours now\": \`kd_query_knn\` with the state carried from query to query, as the eye pass does;"
  echo "FLANN: one \`knnSearch\` call over the same queries (instructions are not time: ours runs AVX2)."
  echo
  cat "$tmp/icount.md"
  echo
  echo "## Heaviest cells at full resolution (1024x768, S=2, P_e=500k, n=100, 1 thread)"
  echo
  echo "Median of $HREPS runs (build/photonmap, times from --stats); peak RSS from /usr/bin/time -v (max)."
  echo
  echo "| method | eye pass (s) | precompute (s) | total (s) | peak RSS (KiB) |"
  echo "|---|---:|---:|---:|---:|"
  cat "$tmp/heavy.md"
  echo
  echo "## Where the time goes (perf, cpu-clock, a whole run of build/photonmap at 1024x768, S=2, P_e=500k, 1 thread)"
  echo
  echo "Conventional, n = 100:"
  echo
  cat "$tmp/prof_conv.txt"
  echo
  echo "Precomputed, n = 100:"
  echo
  cat "$tmp/prof_pre.txt"
  echo
  echo "Precomputed, n = 10:"
  echo
  cat "$tmp/prof_pre10.txt"
  echo
  echo "## Final gathering at full size (pbrt-v2's radiance-photon setting, one thread)"
  echo
  cat "$tmp/gather.md"
  echo
  demote results/bench/scaling.md
  echo
  demote results/bench/threads.md
  echo
  cat experiments/bench/kdtree-notes.md
} > "$OUT.tmp"
mv "$OUT.tmp" "$OUT"
echo "bench: wrote $OUT" >&2
# the same peers section on its own with its raw timings (what findings.py
# reads), as `make bench-peers` writes them
peers_files "experiments/bench/run.sh (\`make bench\`)"
