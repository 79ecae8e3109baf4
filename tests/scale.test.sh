#!/usr/bin/env bash
# scale.test.sh: the scaling benchmark's fit and its end-to-end run.
# scaling.py on a made-up CSV with known exponents (trace ~ P, build ~ P^1.5,
# eye pass constant) must report slopes 1.00, 1.50 and 0.00 (the negative
# control: a constant cost does not read as linear); scaling.sh at two tiny
# counts must write the CSV (columns by name, one row per method and count,
# bytes per stored photon = peak RSS / stored), the Markdown and the PNG;
# the peak is the --repeats 1 process's (memory held by the timed process
# must not show, memory held by that one must); and a renderer that fails
# leaves no result behind. The peak-memory
# estimate against the measured peak is the unit test photons_peak_memory.
cd "$(dirname "$0")/.." || exit 1
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}

if ! "$PY" -c "import numpy, scipy, matplotlib" 2>/dev/null; then
  echo "skipped: numpy, scipy or matplotlib missing for $PY"
  echo "0 passed, 0 failed, 1 skipped"
  exit 0
fi

synthetic() {
  {
    echo "method,photons_emitted,photons_stored,representatives,threads,trace_s,build_s,precompute_s,eye_s,total_s,peak_rss_bytes,bytes_per_stored"
    for p in 1000 10000 100000 1000000; do
      "$PY" -c "p=$p; print('conventional,%d,%d,0,2,%r,%r,0,2.5,%r,%d,45.0' % (p, 3*p, 1e-6*p, 1e-9*p**1.5, 1e-6*p+1e-9*p**1.5+2.5, 135*p))"
    done
  } > "$TMP/syn.csv"
  "$PY" experiments/bench/scaling.py "$TMP/syn.csv" --md "$TMP/syn.md" --png "$TMP/syn.png"
}
check "scaling.py fits known slopes" bash -c "
  $(declare -f synthetic); PY='$PY'; TMP='$TMP'; synthetic || exit 1
  grep -E '^\| trace \| 1\.00 ' '$TMP/syn.md' && grep -E '^\| build \| 1\.50 ' '$TMP/syn.md' &&
  grep -E '^\| eye pass \| (-)?0\.00 ' '$TMP/syn.md' && grep -E '^\| peak bytes per stored photon \| (-)?0\.00 ' '$TMP/syn.md'"
check "negative control: a constant phase does not read as linear" bash -c "
  ! grep -E '^\| eye pass \| 1\.00 ' '$TMP/syn.md'"
check "scaling.py writes a PNG" bash -c "head -c 8 '$TMP/syn.png' | od -An -c | grep -q 'P   N   G'"

if [ ! -x "$PM" ] || [ ! -x /usr/bin/time ]; then
  echo "skipped: the end-to-end run needs $PM and /usr/bin/time"
else
  # a copy of the repository's layout in a scratch directory, so that the
  # real results/ stay as they are
  W="$TMP/w"
  mkdir -p "$W/experiments/bench" "$W/scenes" "$W/build"
  cp experiments/bench/scaling.sh experiments/bench/scaling.py "$W/experiments/bench/"
  cp scenes/cornell.scene "$W/scenes/"
  cp "$PM" "$W/build/photonmap"
  check "scaling.sh end to end at 2000 and 4000 photons" bash -c "
    SCALING_PHOTONS=2000,4000 SCALING_THREADS=2 SCALING_REPEATS=2 PYTHON='$PY' bash '$W/experiments/bench/scaling.sh' build/photonmap || exit 1
    '$PY' - '$W/results/bench/scaling.csv' <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [(r['method'], r['photons_emitted']) for r in rows] == [
    ('conventional', '2000'), ('conventional', '4000'), ('precomputed', '2000'), ('precomputed', '4000')], rows
for r in rows:
    stored = int(r['photons_stored'])
    assert stored > 0 and float(r['trace_s']) > 0 and float(r['eye_s']) > 0, r
    assert abs(float(r['bytes_per_stored']) - int(r['peak_rss_bytes']) / stored) < 0.01, r
    assert (float(r['precompute_s']) > 0) == (r['method'] == 'precomputed'), r
    assert r['repeats'] == '2', r
EOF
    test -s '$W/results/bench/scaling.md' && test -s '$W/results/figures/bench-scaling.png' &&
    grep -q '^## precomputed' '$W/results/bench/scaling.md'"
  # the peak memory is the --repeats 1 process's: a wrapper that holds 300 MiB
  # in the timed process (--repeats 2) leaves the column below that; the
  # control holds them in the --repeats 1 process, and the column must show it
  hold="b = bytearray(300 << 20); b[::4096] = b'x' * len(b[::4096])"
  {
    echo '#!/bin/sh'
    echo 'case " $* " in'
    echo "  *' --repeats 1 '*) [ -z \"\${HOLD_ONE:-}\" ] || '$PY' -c \"$hold\" ;;"
    echo "  *) [ -z \"\${HOLD_TIMED:-}\" ] || '$PY' -c \"$hold\" ;;"
    echo 'esac'
    echo "exec '$W/build/photonmap' \"\$@\""
  } > "$W/build/holder"
  chmod +x "$W/build/holder"
  peak_of() {
    env "$1=1" SCALING_PHOTONS=2000 SCALING_THREADS=1 SCALING_REPEATS=2 PYTHON="$PY" \
      bash "$W/experiments/bench/scaling.sh" build/holder 2> /dev/null || return 1
    "$PY" -c "import csv, sys; print(max(int(r['peak_rss_bytes']) for r in csv.DictReader(open(sys.argv[1]))))" \
      "$W/results/bench/scaling.csv"
  }
  check "the peak memory is the --repeats 1 process's, not the timed one's" bash -c "
    $(declare -f peak_of); PY='$PY'; W='$W'; p=\$(peak_of HOLD_TIMED) && test \"\$p\" -lt \$((300 << 20))"
  check "negative control: memory held in the --repeats 1 process shows in the column" bash -c "
    $(declare -f peak_of); PY='$PY'; W='$W'; p=\$(peak_of HOLD_ONE) && test \"\$p\" -ge \$((300 << 20))"
  # negative control: a renderer that fails leaves no result
  rm -rf "$W/results"
  printf '#!/bin/sh\nexit 1\n' > "$W/build/fail"
  chmod +x "$W/build/fail"
  check "negative control: a failing render leaves no result" bash -c "
    ! SCALING_PHOTONS=2000 SCALING_THREADS=2 PYTHON='$PY' bash '$W/experiments/bench/scaling.sh' build/fail 2>/dev/null &&
    test ! -e '$W/results/bench/scaling.csv' && test ! -e '$W/results/bench/scaling.md'"
fi
finish
